/* test_mesh.c: unit tests of the background mesh (MODEL.md section 3).
 *
 * Checked from the definitions: validation messages, name tables, storage
 * numbering and periodic aliasing, wrapping, unit lookup on boundaries, the
 * diagonal rules, and the element basis: T3 reproduces every linear field and
 * Q4 every bilinear field, values and gradients. The same for a mesh of
 * boxes (dim = 3): validation of the third axis, storage numbering with
 * every combination of periodic axes and the hexahedron corner order,
 * location on faces and across periods, and the trilinear basis (linear
 * fields reproduced, hand values).
 *
 * Tolerances: the fields below are O(1) on an O(1) domain and each basis sum
 * has at most 4 terms, so round-off is a few 1e-16 for values and a few
 * 1e-16 / dx (dx ~ 0.1) for gradients; 1e-12 leaves a wide margin while any
 * wrong weight or triangle gives O(0.01) or more. */
#include <check.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "box.h"
#include "mesh/mesh.h"
#include "plane.h"

#define TOL 1e-12

/* xorshift64* generator; state passed by the caller. */
static double rnd(uint64_t *s)
{
  *s ^= *s >> 12;
  *s ^= *s << 25;
  *s ^= *s >> 27;
  return (double)((*s * 0x2545F4914F6CDD1DULL) >> 11) * 0x1.0p-53;
}

/* A set-up mesh with distinct dx, dy and an offset origin. */
static mpm_mesh make_mesh(int topo, int diag, int px, int py)
{
  mpm_mesh m;
  memset(&m, 0, sizeof m);
  m.nx = 7;
  m.ny = 5;
  m.x0 = -0.4;
  m.y0 = 0.25;
  m.dx = 0.13;
  m.dy = 0.11;
  m.topology = topo;
  m.diagonal = diag;
  m.mirror_x = m.x0 + 3 * m.dx;  /* on a node line */
  m.periodic_x = px;
  m.periodic_y = py;
  mpm_err err = {0};
  ck_assert_int_eq(mpm_mesh_setup(&m, &err), MPM_OK);
  return m;
}

/* Position of storage node id, shifted by whole periods to lie nearest to
 * (xp, yp): the logical node a point near a periodic edge actually touches. */
static void node_near(const mpm_mesh *m, int id, double xp, double yp,
                      double *x, double *y)
{
  plane_node_pos(m, id % m->snx, id / m->snx, x, y);
  if (m->periodic_x)
    *x += m->lx * round((xp - *x) / m->lx);
  if (m->periodic_y)
    *y += m->ly * round((yp - *y) / m->ly);
}

/* ------------------------------------------------------------ setup */

START_TEST(t_setup_derived)
{
  mpm_mesh m = make_mesh(MPM_TOPO_Q4, MPM_DIAG_SLASH, 0, 0);
  ck_assert_int_eq(m.snx, 8);
  ck_assert_int_eq(m.sny, 6);
  ck_assert_int_eq(m.nnodes, 48);
  ck_assert_double_eq_tol(m.lx, 7 * 0.13, TOL);
  ck_assert_double_eq_tol(m.ly, 5 * 0.11, TOL);
  ck_assert_double_eq_tol(m.idx * m.dx, 1.0, TOL);
  ck_assert_double_eq_tol(m.idy * m.dy, 1.0, TOL);
  mpm_mesh p = make_mesh(MPM_TOPO_T3, MPM_DIAG_MIRROR, 1, 0);
  ck_assert_int_eq(p.snx, 7);
  ck_assert_int_eq(p.sny, 6);
  ck_assert_int_eq(p.nnodes, 42);
  mpm_mesh q = make_mesh(MPM_TOPO_T3, MPM_DIAG_BACKSLASH, 1, 1);
  ck_assert_int_eq(q.nnodes, 35);
}
END_TEST

/* Expect mpm_mesh_setup to fail with MPM_EINPUT and a message naming key. */
static void expect_reject(mpm_mesh m, const char *key)
{
  mpm_err err = {0};
  ck_assert_int_eq(mpm_mesh_setup(&m, &err), MPM_EINPUT);
  ck_assert_int_eq(err.code, MPM_EINPUT);
  ck_assert_msg(strstr(err.msg, key) != NULL, "'%s' does not name %s", err.msg,
                key);
  ck_assert_msg(strstr(err.msg, "allowed") || strstr(err.msg, "not finite"),
                "'%s' states no allowed range", err.msg);
}

START_TEST(t_setup_rejects)
{
  const mpm_mesh ok = make_mesh(MPM_TOPO_T3, MPM_DIAG_MIRROR, 0, 0);
  mpm_mesh m;
  m = ok; m.nx = 0; expect_reject(m, "mesh.nx");
  m = ok; m.ny = -3; expect_reject(m, "mesh.ny");
  m = ok; m.dx = 0.0; expect_reject(m, "mesh.dx");
  m = ok; m.dx = -0.1; expect_reject(m, "mesh.dx");
  m = ok; m.dx = NAN; expect_reject(m, "mesh.dx");
  m = ok; m.dx = INFINITY; expect_reject(m, "mesh.dx");
  m = ok; m.dy = NAN; expect_reject(m, "mesh.dy");
  m = ok; m.dy = -INFINITY; expect_reject(m, "mesh.dy");
  m = ok; m.x0 = NAN; expect_reject(m, "mesh.x0");
  m = ok; m.y0 = INFINITY; expect_reject(m, "mesh.y0");
  m = ok; m.dx = 1e308; expect_reject(m, "mesh.dx");  /* nx dx overflows */
  m = ok; m.topology = 2; expect_reject(m, "mesh.topology");
  m = ok; m.topology = -1; expect_reject(m, "mesh.topology");
  m = ok; m.diagonal = 3; expect_reject(m, "mesh.diagonal");
  m = ok; m.diagonal = -1; expect_reject(m, "mesh.diagonal");
  m = ok; m.mirror_x = NAN; expect_reject(m, "mesh.mirror_x");
  m = ok; m.periodic_x = 1; m.nx = 0; expect_reject(m, "mesh.nx");
  m = ok; m.periodic_y = 1; m.ny = 0; expect_reject(m, "mesh.ny");
  m = ok; m.periodic_x = 2; expect_reject(m, "mesh.periodic_x");
  m = ok; m.nx = 100000; m.ny = 100000; expect_reject(m, "nodes");
  /* the same NaN mirror is irrelevant for Q4 and for a fixed diagonal */
  m = ok; m.mirror_x = NAN; m.topology = MPM_TOPO_Q4;
  mpm_err err = {0};
  ck_assert_int_eq(mpm_mesh_setup(&m, &err), MPM_OK);
  /* single units are fine, periodic or not: a periodic axis of one unit
   * stores one node column (row), both edges of the unit */
  m = ok; m.nx = 1; m.ny = 1;
  ck_assert_int_eq(mpm_mesh_setup(&m, &err), MPM_OK);
  ck_assert_int_eq(m.nnodes, 4);
  m = ok; m.nx = 1; m.periodic_x = 1;
  ck_assert_int_eq(mpm_mesh_setup(&m, &err), MPM_OK);
  ck_assert_int_eq(m.snx, 1);
  ck_assert_int_eq(m.nnodes, m.ny + 1);
  ck_assert_int_eq(plane_node(&m, 1, 2), plane_node(&m, 0, 2));
}
END_TEST

START_TEST(t_names)
{
  ck_assert_int_eq(mpm_mesh_topology_from_name("q4"), MPM_TOPO_Q4);
  ck_assert_int_eq(mpm_mesh_topology_from_name("t3"), MPM_TOPO_T3);
  ck_assert_int_eq(mpm_mesh_topology_from_name("t6"), -1);
  ck_assert_int_eq(mpm_mesh_topology_from_name(""), -1);
  ck_assert_int_eq(mpm_mesh_topology_from_name(NULL), -1);
  ck_assert_int_eq(mpm_mesh_diagonal_from_name("/"), MPM_DIAG_SLASH);
  ck_assert_int_eq(mpm_mesh_diagonal_from_name("\\"), MPM_DIAG_BACKSLASH);
  ck_assert_int_eq(strlen("\\"), 1);
  ck_assert_int_eq(mpm_mesh_diagonal_from_name("mirror"), MPM_DIAG_MIRROR);
  ck_assert_int_eq(mpm_mesh_diagonal_from_name("\\\\"), -1);
  ck_assert_int_eq(mpm_mesh_diagonal_from_name("//"), -1);
  ck_assert_int_eq(mpm_mesh_diagonal_from_name("mirrors"), -1);
  ck_assert_int_eq(mpm_mesh_diagonal_from_name(NULL), -1);
}
END_TEST

/* ------------------------------------------------------------ nodes */

START_TEST(t_node_storage)
{
  for (int px = 0; px < 2; px++)
    for (int py = 0; py < 2; py++) {
      mpm_mesh m = make_mesh(MPM_TOPO_Q4, MPM_DIAG_SLASH, px, py);
      int *hit = calloc((size_t)m.nnodes, sizeof *hit);
      for (int j = 0; j <= m.ny; j++)
        for (int i = 0; i <= m.nx; i++) {
          int id = plane_node(&m, i, j);
          ck_assert_int_ge(id, 0);
          ck_assert_int_lt(id, m.nnodes);
          int is = (px && i == m.nx) ? 0 : i, js = (py && j == m.ny) ? 0 : j;
          ck_assert_int_eq(id, js * m.snx + is);
          hit[id]++;
        }
      for (int k = 0; k < m.nnodes; k++)  /* every stored node is used */
        ck_assert_int_ge(hit[k], 1);
      free(hit);
      for (int j = 0; j <= m.ny; j++) {   /* aliasing of the periodic edges */
        if (px)
          ck_assert_int_eq(plane_node(&m, m.nx, j), plane_node(&m, 0, j));
        else
          ck_assert_int_ne(plane_node(&m, m.nx, j), plane_node(&m, 0, j));
      }
      for (int i = 0; i <= m.nx; i++) {
        if (py)
          ck_assert_int_eq(plane_node(&m, i, m.ny), plane_node(&m, i, 0));
        else
          ck_assert_int_ne(plane_node(&m, i, m.ny), plane_node(&m, i, 0));
      }
      if (px && py)
        ck_assert_int_eq(plane_node(&m, m.nx, m.ny), 0);
    }
}
END_TEST

START_TEST(t_node_pos)
{
  mpm_mesh m = make_mesh(MPM_TOPO_Q4, MPM_DIAG_SLASH, 1, 0);
  double x, y;
  plane_node_pos(&m, 3, 2, &x, &y);
  ck_assert_double_eq_tol(x, -0.4 + 3 * 0.13, TOL);
  ck_assert_double_eq_tol(y, 0.25 + 2 * 0.11, TOL);
  plane_node_pos(&m, m.nx, 0, &x, &y);  /* logical, not wrapped */
  ck_assert_double_eq_tol(x, -0.4 + m.lx, TOL);
  ck_assert_double_eq_tol(y, 0.25, TOL);
}
END_TEST

/* ------------------------------------------------------- wrap, unit */

START_TEST(t_wrap)
{
  mpm_mesh m = make_mesh(MPM_TOPO_Q4, MPM_DIAG_SLASH, 1, 0);
  double x = m.x0 + m.lx + 0.3 * m.dx, y = m.y0 - 0.2;
  plane_wrap(&m, &x, &y);
  ck_assert_double_eq_tol(x, m.x0 + 0.3 * m.dx, TOL);
  ck_assert(y == m.y0 - 0.2);                     /* y not periodic: untouched */
  x = m.x0 - 2.5 * m.lx;                          /* several periods */
  plane_wrap(&m, &x, &y);
  ck_assert_double_eq_tol(x, m.x0 + 0.5 * m.lx, TOL);
  x = m.x0 + m.lx;                                /* the right edge is x0 */
  plane_wrap(&m, &x, &y);
  ck_assert_double_eq_tol(x, m.x0, TOL);
  x = m.x0 + 0.123;                               /* inside: bit-identical */
  plane_wrap(&m, &x, &y);
  ck_assert(x == m.x0 + 0.123);
  x = -1e-300 + m.x0;
  plane_wrap(&m, &x, &y);
  ck_assert(x >= m.x0 && x < m.x0 + m.lx);
  mpm_mesh b = make_mesh(MPM_TOPO_Q4, MPM_DIAG_SLASH, 0, 1);
  x = 10.0;
  y = b.y0 + 3.25 * b.ly;
  plane_wrap(&b, &x, &y);
  ck_assert(x == 10.0);
  ck_assert_double_eq_tol(y, b.y0 + 0.25 * b.ly, TOL);
}
END_TEST

START_TEST(t_unit_lookup)
{
  mpm_mesh m = make_mesh(MPM_TOPO_Q4, MPM_DIAG_SLASH, 0, 0);
  int i = -9, j = -9;
  ck_assert_int_eq(plane_unit(&m, m.x0 + 2.5 * m.dx, m.y0 + 1.5 * m.dy, &i, &j),
                   MPM_OK);
  ck_assert_int_eq(i, 2);
  ck_assert_int_eq(j, 1);
  /* corners of the domain */
  ck_assert_int_eq(plane_unit(&m, m.x0, m.y0, &i, &j), MPM_OK);
  ck_assert_int_eq(i, 0);
  ck_assert_int_eq(j, 0);
  ck_assert_int_eq(plane_unit(&m, m.x0 + m.lx, m.y0 + m.ly, &i, &j), MPM_OK);
  ck_assert_int_eq(i, m.nx - 1);   /* right/top boundary: last unit */
  ck_assert_int_eq(j, m.ny - 1);
  /* an interior unit boundary belongs to the unit above / to the right */
  ck_assert_int_eq(plane_unit(&m, m.x0 + 0.5 * m.dx, m.y0 + 2 * m.dy, &i, &j),
                   MPM_OK);
  ck_assert_int_eq(j, 2);
  /* just outside each edge, and non-finite */
  const double e = 1e-12;
  ck_assert_int_eq(plane_unit(&m, m.x0 - e, m.y0 + 0.1, &i, &j), MPM_EOUTSIDE);
  ck_assert_int_eq(plane_unit(&m, m.x0 + m.lx + e, m.y0 + 0.1, &i, &j),
                   MPM_EOUTSIDE);
  ck_assert_int_eq(plane_unit(&m, m.x0 + 0.1, m.y0 - e, &i, &j), MPM_EOUTSIDE);
  ck_assert_int_eq(plane_unit(&m, m.x0 + 0.1, m.y0 + m.ly + e, &i, &j),
                   MPM_EOUTSIDE);
  ck_assert_int_eq(plane_unit(&m, NAN, m.y0 + 0.1, &i, &j), MPM_EOUTSIDE);
  ck_assert_int_eq(plane_unit(&m, m.x0 + 0.1, INFINITY, &i, &j), MPM_EOUTSIDE);
  /* periodic x wraps, y still bounded */
  mpm_mesh p = make_mesh(MPM_TOPO_Q4, MPM_DIAG_SLASH, 1, 0);
  ck_assert_int_eq(plane_unit(&p, p.x0 - 0.5 * p.dx, p.y0, &i, &j), MPM_OK);
  ck_assert_int_eq(i, p.nx - 1);
  ck_assert_int_eq(plane_unit(&p, p.x0 + p.lx + 1.5 * p.dx, p.y0, &i, &j),
                   MPM_OK);
  ck_assert_int_eq(i, 1);
  ck_assert_int_eq(plane_unit(&p, p.x0 + p.lx, p.y0, &i, &j), MPM_OK);
  ck_assert_int_eq(i, 0);  /* x0 + lx is x0 on a periodic axis */
  ck_assert_int_eq(plane_unit(&p, p.x0, p.y0 - e, &i, &j), MPM_EOUTSIDE);
  ck_assert_int_eq(plane_unit(&p, NAN, p.y0, &i, &j), MPM_EOUTSIDE);
  ck_assert_int_eq(plane_unit(&p, -INFINITY, p.y0, &i, &j), MPM_EOUTSIDE);
  /* a huge coordinate has no meaningful period: either answer, but no UB */
  if (plane_unit(&p, 1e300, p.y0, &i, &j) == MPM_OK) {
    ck_assert_int_ge(i, 0);
    ck_assert_int_lt(i, p.nx);
  }
}
END_TEST

START_TEST(t_diagonal_rule)
{
  mpm_mesh s = make_mesh(MPM_TOPO_T3, MPM_DIAG_SLASH, 0, 0);
  mpm_mesh b = make_mesh(MPM_TOPO_T3, MPM_DIAG_BACKSLASH, 0, 0);
  mpm_mesh r = make_mesh(MPM_TOPO_T3, MPM_DIAG_MIRROR, 0, 0);
  for (int i = 0; i < s.nx; i++)
    for (int j = 0; j < s.ny; j++) {
      ck_assert_int_eq(mpm_mesh_column_is_slash(&s, i), 1);
      ck_assert_int_eq(mpm_mesh_column_is_slash(&b, i), 0);
      /* mirror line at node column 3: units 0..2 "/", 3.. "\" */
      ck_assert_int_eq(mpm_mesh_column_is_slash(&r, i), i < 3);
    }
}
END_TEST

/* ------------------------------------------------------------ basis */

/* Triangle nodes actually selected: which corner ids appear. */
static int has_node(const int *node, int n, int id)
{
  for (int k = 0; k < n; k++)
    if (node[k] == id)
      return 1;
  return 0;
}

START_TEST(t_t3_triangle_choice)
{
  mpm_mesh s = make_mesh(MPM_TOPO_T3, MPM_DIAG_SLASH, 0, 0);
  mpm_mesh b = make_mesh(MPM_TOPO_T3, MPM_DIAG_BACKSLASH, 0, 0);
  int node[4];
  double N[4], gx[4], gy[4];
  const int n00 = plane_node(&s, 2, 1), n10 = plane_node(&s, 3, 1);
  const int n11 = plane_node(&s, 3, 2), n01 = plane_node(&s, 2, 2);
  /* "/" unit, (u, v) = (0.7, 0.2): lower-right triangle 00 10 11 */
  double x = s.x0 + 2.7 * s.dx, y = s.y0 + 1.2 * s.dy;
  ck_assert_int_eq(plane_basis(&s, x, y, node, N, gx, gy), 3);
  ck_assert(has_node(node, 3, n00) && has_node(node, 3, n10) &&
            has_node(node, 3, n11));
  /* (0.2, 0.7): upper-left 00 11 01 */
  x = s.x0 + 2.2 * s.dx;
  y = s.y0 + 1.7 * s.dy;
  ck_assert_int_eq(plane_basis(&s, x, y, node, N, gx, gy), 3);
  ck_assert(has_node(node, 3, n00) && has_node(node, 3, n11) &&
            has_node(node, 3, n01));
  /* "\" unit, (0.2, 0.2): lower-left 00 10 01; (0.8, 0.7): 10 11 01 */
  x = b.x0 + 2.2 * b.dx;
  y = b.y0 + 1.2 * b.dy;
  ck_assert_int_eq(plane_basis(&b, x, y, node, N, gx, gy), 3);
  ck_assert(has_node(node, 3, n00) && has_node(node, 3, n10) &&
            has_node(node, 3, n01));
  x = b.x0 + 2.8 * b.dx;
  y = b.y0 + 1.7 * b.dy;
  ck_assert_int_eq(plane_basis(&b, x, y, node, N, gx, gy), 3);
  ck_assert(has_node(node, 3, n10) && has_node(node, 3, n11) &&
            has_node(node, 3, n01));
}
END_TEST

/* Check that the basis of mesh m interpolates f = a + bx + cy + d xy (d = 0
 * for T3) exactly at random points, values and gradients; also N in [0, 1]
 * (the point lies in the returned element) and distinct node ids. */
static void check_reproduction(const mpm_mesh *m, uint64_t *s)
{
  const int want = m->topology == MPM_TOPO_Q4 ? 4 : 3;
  for (int trial = 0; trial < 2000; trial++) {
    const double a = rnd(s) - 0.5, b = 4 * rnd(s) - 2, c = 4 * rnd(s) - 2;
    const double d = m->topology == MPM_TOPO_Q4 ? 4 * rnd(s) - 2 : 0.0;
    /* periodic axes also sample a band beyond the base period */
    const double ex = m->periodic_x ? m->dx : 0.0, ey = m->periodic_y ? m->dy : 0.0;
    const double xp = m->x0 - ex + (m->lx + 2 * ex) * rnd(s);
    const double yp = m->y0 - ey + (m->ly + 2 * ey) * rnd(s);
    int node[4];
    double N[4], gx[4], gy[4];
    ck_assert_int_eq(plane_basis(m, xp, yp, node, N, gx, gy), want);
    double f = 0, fx = 0, fy = 0;
    for (int k = 0; k < want; k++) {
      ck_assert_int_ge(node[k], 0);
      ck_assert_int_lt(node[k], m->nnodes);
      for (int l = 0; l < k; l++)
        ck_assert_int_ne(node[k], node[l]);
      ck_assert(N[k] >= -TOL && N[k] <= 1 + TOL);
      double xi, yi;
      node_near(m, node[k], xp, yp, &xi, &yi);
      const double fi = a + b * xi + c * yi + d * xi * yi;
      f += N[k] * fi;   /* sum N_i f_i */
      fx += gx[k] * fi; /* sum dN_i/dx f_i */
      fy += gy[k] * fi;
    }
    ck_assert_double_eq_tol(f, a + b * xp + c * yp + d * xp * yp, TOL);
    ck_assert_double_eq_tol(fx, b + d * yp, TOL);
    ck_assert_double_eq_tol(fy, c + d * xp, TOL);
  }
}

START_TEST(t_basis_reproduction)
{
  uint64_t s = 0x9E3779B97F4A7C15ULL;
  const int topo[4] = {MPM_TOPO_Q4, MPM_TOPO_T3, MPM_TOPO_T3, MPM_TOPO_T3};
  const int diag[4] = {MPM_DIAG_SLASH, MPM_DIAG_SLASH, MPM_DIAG_BACKSLASH,
                       MPM_DIAG_MIRROR};
  for (int k = 0; k < 4; k++)
    for (int per = 0; per < 4; per++) {
      mpm_mesh m = make_mesh(topo[k], diag[k], per & 1, per >> 1);
      check_reproduction(&m, &s);
    }
}
END_TEST

START_TEST(t_basis_boundary_and_outside)
{
  mpm_mesh m = make_mesh(MPM_TOPO_Q4, MPM_DIAG_SLASH, 0, 0);
  int node[4];
  double N[4], gx[4], gy[4];
  /* top-right corner of the domain: N = 1 on the last node */
  ck_assert_int_eq(plane_basis(&m, m.x0 + m.lx, m.y0 + m.ly, node, N, gx, gy),
                   4);
  const int last = plane_node(&m, m.nx, m.ny);
  for (int k = 0; k < 4; k++)
    ck_assert_double_eq_tol(N[k], node[k] == last ? 1.0 : 0.0, TOL);
  ck_assert_int_eq(plane_basis(&m, m.x0 - 1e-9, m.y0, node, N, gx, gy), -1);
  ck_assert_int_eq(plane_basis(&m, m.x0, m.y0 + m.ly + 1e-9, node, N, gx, gy),
                   -1);
  ck_assert_int_eq(plane_basis(&m, NAN, m.y0, node, N, gx, gy), -1);
  /* periodic: the first node column is reached from the right edge */
  mpm_mesh p = make_mesh(MPM_TOPO_T3, MPM_DIAG_BACKSLASH, 1, 1);
  ck_assert_int_eq(plane_basis(&p, p.x0 + p.lx - 0.25 * p.dx,
                                  p.y0 + p.ly - 0.25 * p.dy, node, N, gx, gy), 3);
  ck_assert(has_node(node, 3, 0));  /* node (nx, ny) is stored as 0 */
  ck_assert_int_eq(plane_basis(&p, INFINITY, p.y0, node, N, gx, gy), -1);
}
END_TEST

/* ------------------------------------------------------------ boxes */

/* Expect mpm_mesh_setup of a mesh of boxes to fail with MPM_EINPUT naming key. */
static void expect_box_reject(mpm_mesh m, const char *key)
{
  mpm_err err = {0};
  ck_assert_int_eq(mpm_mesh_setup(&m, &err), MPM_EINPUT);
  ck_assert_msg(strstr(err.msg, key) != NULL, "'%s' does not name %s", err.msg, key);
}

/* The derived fields of boxes (stored nodes n + 1 per axis, n on a periodic
 * one), and the refusals that concern the third axis: no units, a unit
 * size or origin that is not finite and positive, a periodic axis of one
 * unit (a box would be its own neighbour across a face), a bad periodic
 * flag, more nodes than an int counts; T3 is plane only. */
START_TEST(t_box_setup)
{
  mpm_mesh m = make_box(4, 5, 3, 0);
  ck_assert_int_eq(m.snx, 5);
  ck_assert_int_eq(m.sny, 6);
  ck_assert_int_eq(m.snz, 4);
  ck_assert_int_eq(m.nnodes, 5 * 6 * 4);
  ck_assert_uint_eq(m.nunits, 4 * 5 * 3);
  ck_assert_double_eq_tol(m.lz, 3 * 0.12, TOL);
  ck_assert_double_eq_tol(m.idz, 1.0 / 0.12, TOL);
  mpm_mesh p = make_box(4, 5, 3, 5);               /* x and z periodic */
  ck_assert_int_eq(p.snx, 4);
  ck_assert_int_eq(p.sny, 6);
  ck_assert_int_eq(p.snz, 3);
  ck_assert_int_eq(p.nnodes, 4 * 6 * 3);
  mpm_mesh b = m;
  b.nz = 0;
  expect_box_reject(b, "mesh.nz");
  b = m;
  b.dz = 0.0;
  expect_box_reject(b, "mesh.dz");
  b = m;
  b.z0 = NAN;
  expect_box_reject(b, "mesh.z0");
  b = m;
  b.nz = 1;
  b.periodic_z = 1;
  expect_box_reject(b, "mesh.nz");
  b = m;
  b.periodic_y = 2;
  expect_box_reject(b, "mesh.periodic_y");
  b = m;
  b.nx = b.ny = b.nz = 2000;                       /* 2001^3 nodes > INT_MAX */
  expect_box_reject(b, "mesh.nz");
  b = m;
  b.nx = b.ny = 60000;                             /* 60001^2 x 4 nodes > INT_MAX */
  expect_box_reject(b, "nodes");
  b = m;
  b.topology = MPM_TOPO_T3;
  expect_box_reject(b, "mesh.topology");
  b = m;
  b.dim = 4;
  expect_box_reject(b, "dimension");
}
END_TEST

/* Storage ids of boxes: every logical node maps into [0, nnodes), all are
 * used, aliased nodes (i = nx and i = 0 on a periodic x, ...) share one id,
 * and the unit corners are the hexahedron order of mpm_mesh_node. */
START_TEST(t_box_nodes)
{
  for (int per = 0; per < 8; per++) {
    mpm_mesh m = make_box(3, 4, 2, per);
    int *seen = calloc((size_t)m.nnodes, sizeof *seen);
    for (int k = 0; k <= m.nz; k++)
      for (int j = 0; j <= m.ny; j++)
        for (int i = 0; i <= m.nx; i++) {
          const int id = mpm_mesh_node(&m, i, j, k);
          ck_assert_int_ge(id, 0);
          ck_assert_int_lt(id, m.nnodes);
          seen[id]++;
          if (i == m.nx)
            ck_assert_int_eq(id == mpm_mesh_node(&m, 0, j, k), m.periodic_x);
          if (j == m.ny)
            ck_assert_int_eq(id == mpm_mesh_node(&m, i, 0, k), m.periodic_y);
          if (k == m.nz)
            ck_assert_int_eq(id == mpm_mesh_node(&m, i, j, 0), m.periodic_z);
        }
    const int alias = (m.periodic_x ? 2 : 1) * (m.periodic_y ? 2 : 1) * (m.periodic_z ? 2 : 1);
    for (int id = 0; id < m.nnodes; id++) {
      int ijk[3];
      box_node_ijk(&m, id, ijk);
      const int onx = m.periodic_x && ijk[0] == 0, ony = m.periodic_y && ijk[1] == 0;
      const int onz = m.periodic_z && ijk[2] == 0;
      ck_assert_int_eq(seen[id], (onx ? 2 : 1) * (ony ? 2 : 1) * (onz ? 2 : 1));
      ck_assert_int_le(seen[id], alias);
    }
    free(seen);
    /* one period further is the same node */
    ck_assert_int_eq(mpm_mesh_node(&m, -1, 2, 1) == mpm_mesh_node(&m, m.nx - 1, 2, 1),
                     m.periodic_x);
    const int di[8] = {0, 1, 1, 0, 0, 1, 1, 0}, dj[8] = {0, 0, 1, 1, 0, 0, 1, 1};
    const int dk[8] = {0, 0, 0, 0, 1, 1, 1, 1};
    int c[3];
    for (c[2] = 0; c[2] < m.nz; c[2]++)
      for (c[1] = 0; c[1] < m.ny; c[1]++)
        for (c[0] = 0; c[0] < m.nx; c[0]++) {
          int id[8];
          mpm_mesh_unit_corners(&m, c, id);
          for (int a = 0; a < 8; a++) {
            ck_assert_int_eq(id[a], mpm_mesh_node(&m, c[0] + di[a], c[1] + dj[a], c[2] + dk[a]));
            for (int b = 0; b < a; b++)
              ck_assert_int_ne(id[a], id[b]);
          }
        }
  }
}
END_TEST

/* Location in boxes: inside, on the upper faces (the last unit, local 1),
 * across a period, outside a non-periodic face, not finite. */
START_TEST(t_box_locate)
{
  mpm_mesh m = make_box(4, 5, 3, 4);               /* z periodic */
  int u[3];
  double l[3];
  const double x[3] = {m.x0 + 2.25 * m.dx, m.y0 + 0.5 * m.dy, m.z0 + 1.75 * m.dz};
  ck_assert_int_eq(mpm_mesh_locate(&m, x, u, l), 0);
  ck_assert_int_eq(u[0], 2);
  ck_assert_int_eq(u[1], 0);
  ck_assert_int_eq(u[2], 1);
  ck_assert_double_eq_tol(l[0], 0.25, TOL);
  ck_assert_double_eq_tol(l[1], 0.5, TOL);
  ck_assert_double_eq_tol(l[2], 0.75, TOL);
  const double top[3] = {m.x0 + m.lx, m.y0 + m.ly, m.z0 + 0.5 * m.dz};
  ck_assert_int_eq(mpm_mesh_locate(&m, top, u, l), 0);
  ck_assert_int_eq(u[0], m.nx - 1);
  ck_assert_int_eq(u[1], m.ny - 1);
  ck_assert_double_eq(l[0], 1.0);
  ck_assert_double_eq(l[1], 1.0);
  const double below[3] = {m.x0 + 0.5 * m.dx, m.y0 + 0.5 * m.dy, m.z0 - 0.25 * m.dz};
  ck_assert_int_eq(mpm_mesh_locate(&m, below, u, l), 0);  /* wraps round z */
  ck_assert_int_eq(u[2], m.nz - 1);
  ck_assert_double_eq_tol(l[2], 0.75, 1e-9);
  const double out[3][3] = {{m.x0 - 1e-9, m.y0 + 0.1, m.z0 + 0.1},
                            {m.x0 + 0.1, m.y0 + m.ly + 1e-9, m.z0 + 0.1},
                            {NAN, m.y0 + 0.1, m.z0 + 0.1}};
  for (int q = 0; q < 3; q++)
    ck_assert_int_eq(mpm_mesh_locate(&m, out[q], u, l), -1);
  const double zin[3] = {m.x0 + 0.1, m.y0 + 0.1, INFINITY};
  ck_assert_int_eq(mpm_mesh_locate(&m, zin, u, l), -1);
}
END_TEST

/* The trilinear basis reproduces constants and linear fields (values and
 * gradients; round-off: 8 terms of size 1 or 1/dx ~ 10 /m, far below 1e-12)
 * and has the hand values N_a = f g h, dN_a/dx = (df/du) g h / dx, ...;
 * the values alone (mpm_mesh_shape_corners) are the same numbers. */
START_TEST(t_box_basis)
{
  uint64_t s = 7;
  mpm_mesh m = make_box(4, 5, 3, 3);
  for (int t = 0; t < 200; t++) {
    double xp[3];
    for (int d = 0; d < 3; d++)
      xp[d] = m.periodic[d] ? m.o[d] - m.h[d] + (m.len[d] + 2 * m.h[d]) * rnd(&s)
                            : m.o[d] + m.len[d] * rnd(&s);
    int node[8];
    double N[8], gx[8], gy[8], gz[8];
    double *const dN[3] = {gx, gy, gz};
    ck_assert_int_eq(mpm_mesh_basis(&m, xp, node, N, dN), 8);
    double s0 = 0, g[3] = {0, 0, 0}, mx[3] = {0, 0, 0}, I[3][3] = {{0}};
    for (int a = 0; a < 8; a++) {
      double xi[3];
      box_node_near(&m, node[a], xp, xi);
      const double ga[3] = {gx[a], gy[a], gz[a]};
      s0 += N[a];
      for (int d = 0; d < 3; d++) {
        g[d] += ga[d];
        mx[d] += N[a] * xi[d];
        for (int e = 0; e < 3; e++)
          I[d][e] += xi[d] * ga[e];
      }
    }
    ck_assert_double_eq_tol(s0, 1.0, TOL);
    for (int d = 0; d < 3; d++) {
      ck_assert_double_eq_tol(g[d], 0.0, TOL);
      ck_assert_double_eq_tol(mx[d], xp[d], TOL);
      for (int e = 0; e < 3; e++)
        ck_assert_double_eq_tol(I[d][e], d == e ? 1.0 : 0.0, TOL);
    }
  }
  double N[8], gx[8], gy[8], gz[8];
  double *const dN[3] = {gx, gy, gz};
  const double l[3] = {0.2, 0.3, 0.6};
  mpm_mesh_basis_multilinear(3, l, m.ih, N, dN);
  ck_assert_double_eq_tol(N[0], 0.8 * 0.7 * 0.4, TOL);
  ck_assert_double_eq_tol(N[6], 0.2 * 0.3 * 0.6, TOL);
  ck_assert_double_eq_tol(N[3], 0.8 * 0.3 * 0.4, TOL);
  ck_assert_double_eq_tol(N[5], 0.2 * 0.7 * 0.6, TOL);
  ck_assert_double_eq_tol(gx[0], -0.7 * 0.4 / m.dx, TOL);
  ck_assert_double_eq_tol(gy[0], -0.8 * 0.4 / m.dy, TOL);
  ck_assert_double_eq_tol(gz[0], -0.8 * 0.7 / m.dz, TOL);
  ck_assert_double_eq_tol(gz[6], 0.2 * 0.3 / m.dz, TOL);
  double Nv[8];
  const int c[3] = {1, 2, 0};
  ck_assert_uint_eq(mpm_mesh_shape_corners(&m, c, l, Nv), 0xffu);
  for (int a = 0; a < 8; a++)
    ck_assert(Nv[a] == N[a] || fabs(Nv[a] - N[a]) < 1e-16);
}
END_TEST

int main(void)
{
  Suite *s = suite_create("mesh");
  TCase *tc = tcase_create("mesh");
  tcase_add_test(tc, t_setup_derived);
  tcase_add_test(tc, t_setup_rejects);
  tcase_add_test(tc, t_names);
  tcase_add_test(tc, t_node_storage);
  tcase_add_test(tc, t_node_pos);
  tcase_add_test(tc, t_wrap);
  tcase_add_test(tc, t_unit_lookup);
  tcase_add_test(tc, t_diagonal_rule);
  tcase_add_test(tc, t_t3_triangle_choice);
  tcase_add_test(tc, t_basis_reproduction);
  tcase_add_test(tc, t_basis_boundary_and_outside);
  tcase_add_test(tc, t_box_setup);
  tcase_add_test(tc, t_box_nodes);
  tcase_add_test(tc, t_box_locate);
  tcase_add_test(tc, t_box_basis);
  suite_add_tcase(s, tc);
  SRunner *sr = srunner_create(s);
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf ? EXIT_FAILURE : EXIT_SUCCESS;
}
