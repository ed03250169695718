/* test_shape3.c: unit tests of the 3D mesh of boxes (mesh/box.h) and the 3D
 * shape variants (shape/shape3.h), MODEL.md section 3.
 *
 * The mesh: validation, storage numbering with periodic aliasing, the unit
 * corners, location on faces and across periods, and the trilinear basis
 * (it reproduces every linear field, values and gradients; hand values).
 * The shapes: the kernel invariants of VERIFICATION.md case V0 for delta,
 * ugimp and cpdi on meshes with every combination of periodic axes, at
 * random points with random parallelepiped extents (rotated, sheared, both
 * orientations, wide ones with corners in non-adjacent units),
 *   sum_i S_ip = 1,  sum_i gradS_ip = 0,  sum_i S_ip x_i = x_p,
 *   sum_i x_i (x) gradS_ip = I,
 * node ids valid and distinct, the counts within the variant's span; and
 * hand values: a box extent inside one unit (the corner rule then equals
 * the delta weights: the trilinear N is linear along each axis, and the
 * sign patterns of the corners are independent), a rotated extent (it does
 * not: S_a = N_a(x_p) + the pair terms below), a point on a node, clamped
 * corners, periodic wrap and merged nodes, points outside, non-finite input;
 * the corner geometry against the 2D formula of MODEL.md (D = 2, exactly)
 * and the extent convection against closed forms.
 * Near a periodic face a stencil holds storage ids; each is mapped back to
 * the logical node nearest the point, which is the node the point touches
 * as long as the stencil spans less than half a period (true below, except
 * in the merge test, which checks only sums that need no positions).
 *
 * Tolerances: positions are O(1) m, weights O(1), gradients up to ~30 /m
 * for the most squeezed extents below (1/(8 min|r_k| sin) bounds the
 * corner weights), and a sum has at most 64 terms: round-off is below
 * 64 x 30 x 1.5 x 2.2e-16 ~ 6e-13 in the worst case and was measured at
 * 5e-14 over 160 000 random wide extents, while a wrong weight or sign errs
 * by O(0.01) or more: 1e-12, as in the 2D tests (tests/test_shape.c). Hand
 * values are checked to the same 1e-12. */
#include <check.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "mesh/box.h"
#include "shape/corners.h"
#include "shape/shape.h"
#include "shape/shape3.h"

#define TOL 1e-12
#define W MPM_STENCIL3_W

/* splitmix64 in [0, 1); state passed by the caller. */
static double uni(uint64_t *s)
{
  uint64_t z = (*s += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  z ^= z >> 31;
  return (double)(z >> 11) * 0x1.0p-53;
}

/* A set-up mesh of n^3-ish units with distinct unit sizes and an offset
 * origin; periodic axes from the bits of per (x: 1, y: 2, z: 4). */
static mpm_mesh3 make_mesh3(int nx, int ny, int nz, int per)
{
  mpm_mesh3 m;
  memset(&m, 0, sizeof m);
  m.nx = nx;
  m.ny = ny;
  m.nz = nz;
  m.x0 = -0.4;
  m.y0 = 0.25;
  m.z0 = 0.1;
  m.dx = 0.13;
  m.dy = 0.11;
  m.dz = 0.12;
  m.periodic_x = per & 1;
  m.periodic_y = per >> 1 & 1;
  m.periodic_z = per >> 2 & 1;
  mpm_err err = {0};
  ck_assert_int_eq(mpm_mesh3_setup(&m, &err), MPM_OK);
  return m;
}

/* Logical indices of storage node id. */
static void node_ijk(const mpm_mesh3 *m, int id, int ijk[3])
{
  ijk[0] = id % m->snx;
  ijk[1] = id / m->snx % m->sny;
  ijk[2] = id / (m->snx * m->sny);
}

/* Position of storage node id shifted by whole periods to lie nearest xp. */
static void node_near(const mpm_mesh3 *m, int id, const double xp[3], double x[3])
{
  int ijk[3];
  node_ijk(m, id, ijk);
  mpm_mesh3_node_pos(m, ijk[0], ijk[1], ijk[2], x);
  const int per[3] = {m->periodic_x, m->periodic_y, m->periodic_z};
  const double len[3] = {m->lx, m->ly, m->lz};
  for (int d = 0; d < 3; d++)
    if (per[d])
      x[d] += len[d] * round((xp[d] - x[d]) / len[d]);
}

static double det3(const double r[9])
{
  return r[0] * (r[4] * r[8] - r[7] * r[5]) - r[3] * (r[1] * r[8] - r[7] * r[2]) +
         r[6] * (r[1] * r[5] - r[4] * r[2]);
}

/* Random extent: |r_k| in [lo, hi] min(dx, dy, dz), directions uniform on
 * the sphere, |det R| >= 0.25 |r1| |r2| |r3| (not nearly flat), r3 flipped
 * half the time so both orientations come often. */
static void random_extent(const mpm_mesh3 *m, uint64_t *s, double lo, double hi, double r[9])
{
  const double h = fmin(m->dx, fmin(m->dy, m->dz)), pi = acos(-1.0);
  for (;;) {
    double prod = 1.0;
    for (int k = 0; k < 3; k++) {
      const double a = h * (lo + (hi - lo) * uni(s));
      const double z = 2.0 * uni(s) - 1.0, ph = 2.0 * pi * uni(s), q = sqrt(1.0 - z * z);
      r[3 * k] = a * q * cos(ph);
      r[3 * k + 1] = a * q * sin(ph);
      r[3 * k + 2] = a * z;
      prod *= a;
    }
    if (uni(s) < 0.5)
      for (int d = 0; d < 3; d++)
        r[6 + d] = -r[6 + d];
    if (fabs(det3(r)) >= 0.25 * prod)
      return;
  }
}

/* Random coordinate: on a periodic axis anywhere in [o - h, o + len + h]
 * (beyond the domain too); otherwise at least margin from the faces. */
static double random_coord(uint64_t *s, double o, double len, double h, int periodic,
                           double margin)
{
  if (periodic)
    return o - h + (len + 2 * h) * uni(s);
  return o + margin + (len - 2 * margin) * uni(s);
}

/* A random point of m whose corners (extent r) stay off the non-periodic faces. */
static void random_point(const mpm_mesh3 *m, uint64_t *s, const double r[9], double xp[3])
{
  const double o[3] = {m->x0, m->y0, m->z0}, len[3] = {m->lx, m->ly, m->lz};
  const double h[3] = {m->dx, m->dy, m->dz};
  const int per[3] = {m->periodic_x, m->periodic_y, m->periodic_z};
  for (int d = 0; d < 3; d++) {
    const double margin = fabs(r[d]) + fabs(r[3 + d]) + fabs(r[6 + d]);
    xp[d] = random_coord(s, o[d], len[d], h[d], per[d], margin);
  }
}

/* Evaluate type at (xp, r): ids valid and distinct, the count within the
 * span (width and reach along each axis), and the four invariants; returns
 * the node count. */
static int check_invariants(const mpm_mesh3 *m, const mpm_shape3_type *type, const double xp[3],
                            const double r[9])
{
  int node[W];
  double S[W], gx[W], gy[W], gz[W];
  const int n = type->eval(m, xp, r, node, S, gx, gy, gz);
  int width, reach;
  type->span(m, 1, r, &width, &reach);
  ck_assert_int_ge(n, 8);
  ck_assert_int_le(n, width);
  ck_assert_int_le(width, W);
  const double o[3] = {m->x0, m->y0, m->z0}, h[3] = {m->dx, m->dy, m->dz};
  double s0 = 0, g[3] = {0, 0, 0}, mx[3] = {0, 0, 0}, I[3][3] = {{0}};
  for (int k = 0; k < n; k++) {
    ck_assert_int_ge(node[k], 0);
    ck_assert_int_lt(node[k], m->nnodes);
    for (int l = 0; l < k; l++)
      ck_assert_int_ne(node[k], node[l]);       /* merged: each node once */
    double xi[3];
    node_near(m, node[k], xp, xi);
    const double gk[3] = {gx[k], gy[k], gz[k]};
    s0 += S[k];
    for (int a = 0; a < 3; a++) {
      /* node index along a from the point's unit: -reach .. 1 + reach */
      const double li = round((xi[a] - o[a]) / h[a]), ui = floor((xp[a] - o[a]) / h[a]);
      ck_assert_double_ge(li - ui, -reach);
      ck_assert_double_le(li - ui, 1 + reach);
      g[a] += gk[a];
      mx[a] += S[k] * xi[a];
      for (int b = 0; b < 3; b++)
        I[a][b] += xi[a] * gk[b];
    }
  }
  ck_assert_double_eq_tol(s0, 1.0, TOL);
  for (int a = 0; a < 3; a++) {
    ck_assert_double_eq_tol(g[a], 0.0, TOL);
    ck_assert_double_eq_tol(mx[a], xp[a], TOL);  /* the logical position nearest xp */
    for (int b = 0; b < 3; b++)
      ck_assert_double_eq_tol(I[a][b], a == b ? 1.0 : 0.0, TOL);
  }
  return n;
}

/* The invariants on n x n x n units with each combination of periodic axes;
 * returns how many extents had det R < 0. */
static int invariants_on(const mpm_shape3_type *type, double rlo, double rhi, int n,
                         int trials, uint64_t seed)
{
  uint64_t s = seed;
  int neg = 0;
  for (int per = 0; per < 8; per++) {
    mpm_mesh3 m = make_mesh3(n, n + 1, n - 1, per);
    for (int t = 0; t < trials; t++) {
      double r[9], xp[3];
      random_extent(&m, &s, rlo, rhi, r);
      random_point(&m, &s, r, xp);
      neg += det3(r) < 0.0;
      check_invariants(&m, type, xp, r);
    }
  }
  return neg;
}

/* ---------------------------------------------------------------- mesh */

/* Expect mpm_mesh3_setup to fail with MPM_EINPUT naming key. */
static void expect_bad(mpm_mesh3 m, const char *key)
{
  mpm_err err = {0};
  ck_assert_int_eq(mpm_mesh3_setup(&m, &err), MPM_EINPUT);
  ck_assert_msg(strstr(err.msg, key) != NULL, "'%s' does not name %s", err.msg, key);
}

START_TEST(t_mesh3_setup)
{
  mpm_mesh3 m = make_mesh3(4, 5, 3, 0);
  ck_assert_int_eq(m.snx, 5);
  ck_assert_int_eq(m.sny, 6);
  ck_assert_int_eq(m.snz, 4);
  ck_assert_int_eq(m.nnodes, 5 * 6 * 4);
  ck_assert_double_eq_tol(m.lz, 3 * 0.12, TOL);
  ck_assert_double_eq_tol(m.idz, 1.0 / 0.12, TOL);
  mpm_mesh3 p = make_mesh3(4, 5, 3, 5);           /* x and z periodic */
  ck_assert_int_eq(p.snx, 4);
  ck_assert_int_eq(p.sny, 6);
  ck_assert_int_eq(p.snz, 3);
  ck_assert_int_eq(p.nnodes, 4 * 6 * 3);
  mpm_mesh3 b = m;
  b.nz = 0;
  expect_bad(b, "mesh.nz");
  b = m;
  b.dz = 0.0;
  expect_bad(b, "mesh.dz");
  b = m;
  b.z0 = NAN;
  expect_bad(b, "mesh.z0");
  b = m;
  b.nz = 1;
  b.periodic_z = 1;
  expect_bad(b, "mesh.nz");
  b = m;
  b.periodic_y = 2;
  expect_bad(b, "mesh.periodic_y");
  b = m;
  b.nx = b.ny = b.nz = 2000;                      /* 2001^3 nodes > INT_MAX */
  expect_bad(b, "mesh.nz");
  b = m;
  b.nx = b.ny = 60000;                            /* one layer already too many */
  expect_bad(b, "nodes");
}
END_TEST

/* Storage ids: every logical node maps into [0, nnodes), all of them are
 * used, aliased nodes (i = nx and i = 0 on a periodic x, ...) share one id,
 * and the unit corners are the hexahedron order of mpm_mesh3_node. */
START_TEST(t_mesh3_nodes)
{
  for (int per = 0; per < 8; per++) {
    mpm_mesh3 m = make_mesh3(3, 4, 2, per);
    int *seen = calloc((size_t)m.nnodes, sizeof *seen);
    for (int k = 0; k <= m.nz; k++)
      for (int j = 0; j <= m.ny; j++)
        for (int i = 0; i <= m.nx; i++) {
          const int id = mpm_mesh3_node(&m, i, j, k);
          ck_assert_int_ge(id, 0);
          ck_assert_int_lt(id, m.nnodes);
          seen[id]++;
          if (i == m.nx)
            ck_assert_int_eq(id == mpm_mesh3_node(&m, 0, j, k), m.periodic_x);
          if (j == m.ny)
            ck_assert_int_eq(id == mpm_mesh3_node(&m, i, 0, k), m.periodic_y);
          if (k == m.nz)
            ck_assert_int_eq(id == mpm_mesh3_node(&m, i, j, 0), m.periodic_z);
        }
    const int alias = (m.periodic_x ? 2 : 1) * (m.periodic_y ? 2 : 1) * (m.periodic_z ? 2 : 1);
    for (int id = 0; id < m.nnodes; id++) {
      int ijk[3];
      node_ijk(&m, id, ijk);
      const int onx = m.periodic_x && ijk[0] == 0, ony = m.periodic_y && ijk[1] == 0;
      const int onz = m.periodic_z && ijk[2] == 0;
      ck_assert_int_eq(seen[id], (onx ? 2 : 1) * (ony ? 2 : 1) * (onz ? 2 : 1));
      ck_assert_int_le(seen[id], alias);
    }
    free(seen);
    /* one period further is the same node */
    ck_assert_int_eq(mpm_mesh3_node(&m, -1, 2, 1) == mpm_mesh3_node(&m, m.nx - 1, 2, 1),
                     m.periodic_x);
    const int di[8] = {0, 1, 1, 0, 0, 1, 1, 0}, dj[8] = {0, 0, 1, 1, 0, 0, 1, 1};
    const int dk[8] = {0, 0, 0, 0, 1, 1, 1, 1};
    for (int k = 0; k < m.nz; k++)
      for (int j = 0; j < m.ny; j++)
        for (int i = 0; i < m.nx; i++) {
          int c[8];
          mpm_mesh3_unit_corners(&m, i, j, k, c);
          for (int a = 0; a < 8; a++) {
            ck_assert_int_eq(c[a], mpm_mesh3_node(&m, i + di[a], j + dj[a], k + dk[a]));
            for (int b = 0; b < a; b++)
              ck_assert_int_ne(c[a], c[b]);
          }
        }
  }
}
END_TEST

/* Location: inside, on the upper faces (the last unit, local 1), across a
 * period, outside a non-periodic face, not finite. */
START_TEST(t_mesh3_locate)
{
  mpm_mesh3 m = make_mesh3(4, 5, 3, 4);           /* z periodic */
  int u[3];
  double l[3];
  const double x[3] = {m.x0 + 2.25 * m.dx, m.y0 + 0.5 * m.dy, m.z0 + 1.75 * m.dz};
  ck_assert_int_eq(mpm_mesh3_locate(&m, x, u, l), 0);
  ck_assert_int_eq(u[0], 2);
  ck_assert_int_eq(u[1], 0);
  ck_assert_int_eq(u[2], 1);
  ck_assert_double_eq_tol(l[0], 0.25, TOL);
  ck_assert_double_eq_tol(l[1], 0.5, TOL);
  ck_assert_double_eq_tol(l[2], 0.75, TOL);
  const double top[3] = {m.x0 + m.lx, m.y0 + m.ly, m.z0 + 0.5 * m.dz};
  ck_assert_int_eq(mpm_mesh3_locate(&m, top, u, l), 0);
  ck_assert_int_eq(u[0], m.nx - 1);
  ck_assert_int_eq(u[1], m.ny - 1);
  ck_assert_double_eq(l[0], 1.0);
  ck_assert_double_eq(l[1], 1.0);
  const double below[3] = {m.x0 + 0.5 * m.dx, m.y0 + 0.5 * m.dy, m.z0 - 0.25 * m.dz};
  ck_assert_int_eq(mpm_mesh3_locate(&m, below, u, l), 0);  /* wraps round z */
  ck_assert_int_eq(u[2], m.nz - 1);
  ck_assert_double_eq_tol(l[2], 0.75, 1e-9);
  const double out[3][3] = {{m.x0 - 1e-9, m.y0 + 0.1, m.z0 + 0.1},
                            {m.x0 + 0.1, m.y0 + m.ly + 1e-9, m.z0 + 0.1},
                            {NAN, m.y0 + 0.1, m.z0 + 0.1}};
  for (int q = 0; q < 3; q++)
    ck_assert_int_eq(mpm_mesh3_locate(&m, out[q], u, l), -1);
  const double zin[3] = {m.x0 + 0.1, m.y0 + 0.1, INFINITY};
  ck_assert_int_eq(mpm_mesh3_locate(&m, zin, u, l), -1);
}
END_TEST

/* The trilinear basis reproduces constants and linear fields (values and
 * gradients) and has the hand values N_a = f g h. */
START_TEST(t_mesh3_basis)
{
  uint64_t s = 7;
  mpm_mesh3 m = make_mesh3(4, 5, 3, 3);
  for (int t = 0; t < 200; t++) {
    double xp[3];
    const double r0[9] = {0};
    random_point(&m, &s, r0, xp);
    int node[8];
    double N[8], gx[8], gy[8], gz[8];
    ck_assert_int_eq(mpm_mesh3_basis(&m, xp, node, N, gx, gy, gz), 8);
    double s0 = 0, g[3] = {0, 0, 0}, mx[3] = {0, 0, 0}, I[3][3] = {{0}};
    for (int a = 0; a < 8; a++) {
      double xi[3];
      node_near(&m, node[a], xp, xi);
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
  mpm_mesh3_basis_q8(0.2, 0.3, 0.6, m.idx, m.idy, m.idz, N, gx, gy, gz);
  ck_assert_double_eq_tol(N[0], 0.8 * 0.7 * 0.4, TOL);
  ck_assert_double_eq_tol(N[6], 0.2 * 0.3 * 0.6, TOL);
  ck_assert_double_eq_tol(N[3], 0.8 * 0.3 * 0.4, TOL);
  ck_assert_double_eq_tol(N[5], 0.2 * 0.7 * 0.6, TOL);
  ck_assert_double_eq_tol(gx[0], -0.7 * 0.4 / m.dx, TOL);
  ck_assert_double_eq_tol(gy[0], -0.8 * 0.4 / m.dy, TOL);
  ck_assert_double_eq_tol(gz[0], -0.8 * 0.7 / m.dz, TOL);
  ck_assert_double_eq_tol(gz[6], 0.2 * 0.3 / m.dz, TOL);
  double Nv[8];
  mpm_mesh3_shape_q8(0.2, 0.3, 0.6, Nv);
  for (int a = 0; a < 8; a++)
    ck_assert(Nv[a] == N[a] || fabs(Nv[a] - N[a]) < 1e-16);
}
END_TEST

/* ------------------------------------------------------- corner rule */

/* D = 2: the offsets and weights are the 2D formula of MODEL.md, value for
 * value (A = 4 det R; corner 1 w = (1/A)(r1y - r2y, r2x - r1x), corner 2
 * (1/A)(r1y + r2y, -r1x - r2x), corners 3, 4 the negatives). D = 3:
 * sum_c w_c = 0 and sum_c w_c (x) (x_c - x_p) = I, and the corners are the
 * signs of the header's order. */
START_TEST(t_corner_rule)
{
  uint64_t s = 99;
  for (int t = 0; t < 1000; t++) {
    double r[4];
    for (int q = 0; q < 4; q++)
      r[q] = uni(&s) - 0.5;
    double off[8], w[8];
    const double A = mpm_shape_in_corner_rule(2, r, off, w);
    const double r1x = r[0], r1y = r[1], r2x = r[2], r2y = r[3];
    ck_assert(A == 4.0 * (r1x * r2y - r1y * r2x));
    const double iA = 1.0 / A;
    const double ax = (r1y - r2y) * iA, ay = (r2x - r1x) * iA;
    const double bx = (r1y + r2y) * iA, by = -(r1x + r2x) * iA;
    const double wx[4] = {ax, bx, -ax, -bx}, wy[4] = {ay, by, -ay, -by};
    const double ox[4] = {-r1x - r2x, r1x - r2x, r1x + r2x, -r1x + r2x};
    const double oy[4] = {-r1y - r2y, r1y - r2y, r1y + r2y, -r1y + r2y};
    for (int c = 0; c < 4; c++) {
      ck_assert(off[2 * c] == ox[c] && off[2 * c + 1] == oy[c]);
      ck_assert(w[2 * c] == wx[c] && w[2 * c + 1] == wy[c]);
    }
  }
  const int sx[8] = {-1, 1, 1, -1, -1, 1, 1, -1}, sy[8] = {-1, -1, 1, 1, -1, -1, 1, 1};
  const int sz[8] = {-1, -1, -1, -1, 1, 1, 1, 1};
  mpm_mesh3 m = make_mesh3(4, 4, 4, 0);
  for (int t = 0; t < 1000; t++) {
    double r[9], off[24], w[24];
    random_extent(&m, &s, 0.05, 1.5, r);
    const double A = mpm_shape_in_corner_rule(3, r, off, w);
    ck_assert_double_eq_tol(A, 8.0 * det3(r), 1e-15);
    double sw[3] = {0, 0, 0}, I[3][3] = {{0}};
    for (int c = 0; c < 8; c++)
      for (int d = 0; d < 3; d++) {
        ck_assert_double_eq_tol(off[3 * c + d], sx[c] * r[d] + sy[c] * r[3 + d] + sz[c] * r[6 + d],
                                1e-15);
        sw[d] += w[3 * c + d];
        for (int e = 0; e < 3; e++)
          I[d][e] += w[3 * c + d] * off[3 * c + e];
      }
    for (int d = 0; d < 3; d++) {
      ck_assert_double_eq_tol(sw[d], 0.0, TOL);
      for (int e = 0; e < 3; e++)
        ck_assert_double_eq_tol(I[d][e], d == e ? 1.0 : 0.0, TOL);
    }
  }
}
END_TEST

/* ---------------------------------------------------------- invariants */

START_TEST(t_invariants_delta3)
{
  invariants_on(&mpm_shape3_delta, 0.1, 0.5, 6, 150, 0x5EEDULL);
}
END_TEST

START_TEST(t_invariants_ugimp3)
{
  const int neg = invariants_on(&mpm_shape3_ugimp, 0.1, 0.5, 6, 300, 0xC0FFEEULL);
  ck_assert_int_gt(neg, 600);                     /* both orientations, about half each */
  ck_assert_int_lt(neg, 1800);
}
END_TEST

/* Extents up to 1.5 units: corners up to 4.5 units away, in non-adjacent
 * units: up to 64 distinct nodes, listed node by node. */
START_TEST(t_invariants_ugimp3_wide)
{
  invariants_on(&mpm_shape3_ugimp, 0.5, 1.5, 14, 150, 0xBADF00DULL);
  mpm_mesh3 m = make_mesh3(14, 14, 14, 0);
  const double r[9] = {1.2 * m.dx, 0, 0, 0, 1.2 * m.dy, 0, 0, 0, 1.2 * m.dz};
  const double xp[3] = {m.x0 + 7.5 * m.dx, m.y0 + 7.5 * m.dy, m.z0 + 7.5 * m.dz};
  ck_assert_int_eq(check_invariants(&m, &mpm_shape3_ugimp, xp, r), 64);  /* 8 separate units */
}
END_TEST

/* CPDI1 extents as the deformation makes them: sheared, stretched to 1.5
 * units or squeezed to 0.1. */
START_TEST(t_invariants_cpdi3)
{
  invariants_on(&mpm_shape3_cpdi, 0.1, 1.5, 14, 150, 0xFEEDULL);
}
END_TEST

/* ------------------------------------------------------------ by hand */

/* Weights of type at xp: the count; node, S and gradient out. */
static int eval3(const mpm_shape3_type *type, const mpm_mesh3 *m, const double xp[3],
                 const double r[9], int *node, double *S, double (*g)[3])
{
  double gx[W], gy[W], gz[W];
  const int n = type->eval(m, xp, r, node, S, gx, gy, gz);
  for (int k = 0; k < n; k++) {
    g[k][0] = gx[k];
    g[k][1] = gy[k];
    g[k][2] = gz[k];
  }
  return n;
}

/* Slot of storage node id in node[0 .. n), or n. */
static int find(const int *node, int n, int id)
{
  int k = 0;
  while (k < n && node[k] != id)
    k++;
  return k;
}

/* A box extent R = diag(a, b, c) (any signs) inside one unit: the corner
 * average of N_a = f g h over independent signs is f(u) g(v) h(w), and the
 * difference quotients of the linear factors are their slopes, so the
 * weights equal the delta weights. */
START_TEST(t_ugimp3_box_is_delta)
{
  mpm_mesh3 m = make_mesh3(5, 4, 6, 2);
  const double xp[3] = {m.x0 + 2.4 * m.dx, m.y0 + 1.55 * m.dy, m.z0 + 3.3 * m.dz};
  const double boxes[2][9] = {{0.2 * m.dx, 0, 0, 0, 0.15 * m.dy, 0, 0, 0, 0.25 * m.dz},
                              {0.2 * m.dx, 0, 0, 0, -0.3 * m.dy, 0, 0, 0, 0.1 * m.dz}};
  for (int q = 0; q < 2; q++) {
    int na[W], nb[W];
    double Sa[W], Sb[W], ga[W][3], gb[W][3];
    const int a = eval3(&mpm_shape3_delta, &m, xp, boxes[q], na, Sa, ga);
    const int b = eval3(&mpm_shape3_ugimp, &m, xp, boxes[q], nb, Sb, gb);
    ck_assert_int_eq(a, 8);
    ck_assert_int_eq(b, 8);
    for (int k = 0; k < a; k++) {
      const int l = find(nb, b, na[k]);
      ck_assert_int_lt(l, b);
      ck_assert_double_eq_tol(Sb[l], Sa[k], TOL);
      for (int d = 0; d < 3; d++)
        ck_assert_double_eq_tol(gb[l][d], ga[k][d], TOL);
    }
  }
}
END_TEST

/* A rotated extent inside one unit is not the delta weights: with local
 * corner offsets du = s.alpha, dv = s.beta, dw = s.gamma (alpha_k = r_kx/dx,
 * ...), the average over the 8 sign vectors of
 * (f + su du)(g + sv dv)(h + sw dw) keeps, besides f g h, the pair terms
 * (E[s_k s_l] = delta_kl, odd moments vanish):
 *   S_a = N_a(x_p) + su sv h alpha.beta + su sw g alpha.gamma
 *         + sv sw f beta.gamma. */
START_TEST(t_ugimp3_rotated_hand)
{
  mpm_mesh3 m = make_mesh3(5, 4, 6, 0);
  const double u = 0.45, v = 0.5, w = 0.55;
  const double xp[3] = {m.x0 + (2 + u) * m.dx, m.y0 + (1 + v) * m.dy, m.z0 + (3 + w) * m.dz};
  const double c = cos(0.5), sn = sin(0.5), e = 0.2;      /* a box turned about z and x */
  const double r[9] = {e * m.dx * c, e * m.dy * sn, 0.0,
                       -e * m.dx * sn * 0.8, e * m.dy * c * 0.8, 0.3 * e * m.dz,
                       0.0, -0.5 * e * m.dy, e * m.dz};
  double al[3], be[3], ga[3];
  for (int k = 0; k < 3; k++) {
    al[k] = r[3 * k] / m.dx;
    be[k] = r[3 * k + 1] / m.dy;
    ga[k] = r[3 * k + 2] / m.dz;
  }
  const double ab = al[0] * be[0] + al[1] * be[1] + al[2] * be[2];
  const double ag = al[0] * ga[0] + al[1] * ga[1] + al[2] * ga[2];
  const double bg = be[0] * ga[0] + be[1] * ga[1] + be[2] * ga[2];
  ck_assert(fabs(ab) > 1e-3 && fabs(ag) > 1e-3 && fabs(bg) > 1e-3);
  int node[W];
  double S[W], g[W][3];
  ck_assert_int_eq(eval3(&mpm_shape3_ugimp, &m, xp, r, node, S, g), 8);
  int corner[8];
  mpm_mesh3_unit_corners(&m, 2, 1, 3, corner);
  const double su[8] = {-1, 1, 1, -1, -1, 1, 1, -1}, sv[8] = {-1, -1, 1, 1, -1, -1, 1, 1};
  const double sw[8] = {-1, -1, -1, -1, 1, 1, 1, 1};
  for (int a = 0; a < 8; a++) {
    const double f = su[a] > 0 ? u : 1 - u, gg = sv[a] > 0 ? v : 1 - v, h = sw[a] > 0 ? w : 1 - w;
    const double want = f * gg * h + su[a] * sv[a] * h * ab + su[a] * sw[a] * gg * ag +
                        sv[a] * sw[a] * f * bg;
    const int l = find(node, 8, corner[a]);
    ck_assert_int_lt(l, 8);
    ck_assert_double_eq_tol(S[l], want, TOL);
    ck_assert(fabs(want - f * gg * h) > 1e-4);  /* not the delta value */
  }
}
END_TEST

/* Point on node (2, 2, 2) with the cube extent r_k = h e_k, h < dx, dy, dz:
 * every corner sees N of that node = (1 - h/dx)(1 - h/dy)(1 - h/dz), so S is
 * that and gradS = 0; node (3, 3, 3) is seen by one corner: S = N/8 with
 * N = (h/dx)(h/dy)(h/dz); node (3, 2, 2) by the four corners with s_x = +1
 * with N = (h/dx)(1 - h/dy)(1 - h/dz): S = N/2, gradS = (N/(2h), 0, 0). */
START_TEST(t_ugimp3_on_node)
{
  mpm_mesh3 m = make_mesh3(5, 4, 6, 0);
  const double h = 0.03;
  const double r[9] = {h, 0, 0, 0, -h, 0, 0, 0, h};  /* det < 0: the same weights */
  double xp[3];
  mpm_mesh3_node_pos(&m, 2, 2, 2, xp);
  int node[W];
  double S[W], g[W][3];
  ck_assert_int_eq(eval3(&mpm_shape3_ugimp, &m, xp, r, node, S, g), 27);
  const double ux = h / m.dx, uy = h / m.dy, uz = h / m.dz;
  int k = find(node, 27, mpm_mesh3_node(&m, 2, 2, 2));
  ck_assert_int_lt(k, 27);
  ck_assert_double_eq_tol(S[k], (1 - ux) * (1 - uy) * (1 - uz), TOL);
  for (int d = 0; d < 3; d++)
    ck_assert_double_eq_tol(g[k][d], 0.0, TOL);
  k = find(node, 27, mpm_mesh3_node(&m, 3, 3, 3));
  ck_assert_int_lt(k, 27);
  ck_assert_double_eq_tol(S[k], ux * uy * uz / 8, TOL);
  k = find(node, 27, mpm_mesh3_node(&m, 3, 2, 2));
  ck_assert_int_lt(k, 27);
  const double N = ux * (1 - uy) * (1 - uz);
  ck_assert_double_eq_tol(S[k], N / 2, TOL);
  ck_assert_double_eq_tol(g[k][0], N / (2 * h), TOL);
  ck_assert_double_eq_tol(g[k][1], 0.0, TOL);
  ck_assert_double_eq_tol(g[k][2], 0.0, TOL);
  /* listed layer by layer, row by row: node (1, 1, 1) first, (3, 3, 3) last */
  ck_assert_int_eq(node[0], mpm_mesh3_node(&m, 1, 1, 1));
  ck_assert_int_eq(node[26], mpm_mesh3_node(&m, 3, 3, 3));
}
END_TEST

/* Corners beyond a non-periodic face are clamped onto it. Point at
 * (x0 + 0.1 dx, y0 + 2.5 dy, z0 + 1.5 dz), r1 = (0.4 dx, 0, 0),
 * r2 = (0, 0.25 dy, 0), r3 = (0, 0, 0.25 dz): the x corners go to x0
 * (clamped from x0 - 0.3 dx) and x0 + 0.5 dx, so node column 0 takes
 * (1 + 0.5)/2 = 0.75 and column 1 0.25; rows 2, 3 and layers 1, 2 take 1/2
 * each. Centres on faces are inside, just beyond them outside. */
START_TEST(t_ugimp3_clamped)
{
  mpm_mesh3 m = make_mesh3(5, 4, 6, 0);
  const double r[9] = {0.4 * m.dx, 0, 0, 0, 0.25 * m.dy, 0, 0, 0, 0.25 * m.dz};
  const double xp[3] = {m.x0 + 0.1 * m.dx, m.y0 + 2.5 * m.dy, m.z0 + 1.5 * m.dz};
  for (int v = 0; v < 2; v++) {
    const mpm_shape3_type *type = v ? &mpm_shape3_cpdi : &mpm_shape3_ugimp;
    int node[W];
    double S[W], g[W][3];
    const int n = eval3(type, &m, xp, r, node, S, g);
    ck_assert_int_eq(n, 8);
    double s0 = 0, gs[3] = {0, 0, 0};
    for (int k = 0; k < n; k++) {
      int ijk[3];
      node_ijk(&m, node[k], ijk);
      ck_assert_double_eq_tol(S[k], (ijk[0] == 0 ? 0.75 : 0.25) * 0.25, TOL);
      s0 += S[k];
      for (int d = 0; d < 3; d++)
        gs[d] += g[k][d];
    }
    ck_assert_double_eq_tol(s0, 1.0, TOL);        /* partition of unity survives */
    for (int d = 0; d < 3; d++)
      ck_assert_double_eq_tol(gs[d], 0.0, TOL);
  }
  const double big[9] = {0.45 * m.dx, 0.1 * m.dy, 0, -0.1 * m.dx, 0.45 * m.dy, 0.1 * m.dz,
                         0.05 * m.dx, 0, 0.4 * m.dz};
  const double lo[3] = {m.x0, m.y0, m.z0}, hi[3] = {m.x0 + m.lx, m.y0 + m.ly, m.z0 + m.lz};
  int node[W];
  double S[W], g[W][3];
  for (const mpm_shape3_type *const *t = mpm_shape3_table; *t; t++) {
    ck_assert_int_gt(eval3(*t, &m, lo, big, node, S, g), 0);
    ck_assert_int_gt(eval3(*t, &m, hi, big, node, S, g), 0);
    for (int d = 0; d < 3; d++) {
      double a[3] = {m.x0 + 0.1, m.y0 + 0.1, m.z0 + 0.1}, b[3] = {m.x0 + 0.1, m.y0 + 0.1,
                                                                  m.z0 + 0.1};
      a[d] = lo[d] - 1e-9;
      b[d] = hi[d] + 1e-9;
      ck_assert_int_eq(eval3(*t, &m, a, big, node, S, g), -1);
      ck_assert_int_eq(eval3(*t, &m, b, big, node, S, g), -1);
    }
  }
}
END_TEST

/* Along a periodic x the same point is not clamped: the left corners wrap to
 * node column nx - 1 (N = 0.3 there, half the corners: 0.15 along x). One
 * period to the right is the same stencil. On a z of two units a wide extent
 * reaches one stored node from two sides: merged, the sums still hold. */
START_TEST(t_ugimp3_periodic)
{
  mpm_mesh3 m = make_mesh3(5, 4, 6, 1);
  const double r[9] = {0.4 * m.dx, 0, 0, 0, 0.25 * m.dy, 0, 0, 0, 0.25 * m.dz};
  const double xp[3] = {m.x0 + 0.1 * m.dx, m.y0 + 2.5 * m.dy, m.z0 + 1.5 * m.dz};
  int node[W], node2[W];
  double S[W], g[W][3], S2[W], g2[W][3];
  const int n = eval3(&mpm_shape3_ugimp, &m, xp, r, node, S, g);
  ck_assert_int_eq(n, 12);                        /* columns nx-1, 0, 1 x 2 rows x 2 layers */
  int last = 0;
  for (int k = 0; k < n; k++) {
    int ijk[3];
    node_ijk(&m, node[k], ijk);
    if (ijk[0] == m.nx - 1) {
      ck_assert_double_eq_tol(S[k], 0.15 * 0.25, TOL);
      last++;
    }
  }
  ck_assert_int_eq(last, 4);
  const double xq[3] = {xp[0] + m.lx, xp[1], xp[2]};
  ck_assert_int_eq(eval3(&mpm_shape3_ugimp, &m, xq, r, node2, S2, g2), n);
  for (int k = 0; k < n; k++) {
    ck_assert_int_eq(node2[k], node[k]);
    ck_assert_double_eq_tol(S2[k], S[k], TOL);
    for (int d = 0; d < 3; d++)
      ck_assert_double_eq_tol(g2[k][d], g[k][d], TOL);
  }
  /* merging: z periodic on 2 units, an extent of 0.6 units along z (the
   * block: 3 node layers of which two are one stored layer) and one also
   * 1.6 units along x (corners 4 units apart: node by node) */
  mpm_mesh3 t = make_mesh3(5, 4, 2, 4);
  const double rz[2][9] = {{0.3 * t.dx, 0, 0, 0, 0.3 * t.dy, 0, 0.1 * t.dx, 0, 0.6 * t.dz},
                           {1.6 * t.dx, 0, 0, 0, 0.3 * t.dy, 0, 0.1 * t.dx, 0, 0.6 * t.dz}};
  const double xt[3] = {t.x0 + 2.5 * t.dx, t.y0 + 1.5 * t.dy, t.z0 + 0.3 * t.dz};
  for (int q = 0; q < 2; q++) {
    const int c = eval3(&mpm_shape3_ugimp, &t, xt, rz[q], node, S, g);
    if (q == 0)
      ck_assert_int_eq(c, 2 * 2 * 2);             /* only 2 node layers are stored */
    else
      ck_assert_int_le(c, 6 * 2 * 2);
    double s0 = 0, gs[3] = {0, 0, 0};
    for (int k = 0; k < c; k++) {
      ck_assert_int_ge(node[k], 0);
      ck_assert_int_lt(node[k], t.nnodes);
      for (int l = 0; l < k; l++)
        ck_assert_int_ne(node[k], node[l]);
      s0 += S[k];
      for (int d = 0; d < 3; d++)
        gs[d] += g[k][d];
    }
    ck_assert_double_eq_tol(s0, 1.0, TOL);
    for (int d = 0; d < 3; d++)
      ck_assert_double_eq_tol(gs[d], 0.0, TOL);
  }
}
END_TEST

/* Non-finite points and extents are reported as outside (-1), not used; a
 * corner geometry that overflows too; a flat extent (det R = 0) takes the
 * delta weights. */
/* An extent along the axes takes the factorised rule (ugimp3_box): the
 * same extent with r1 and r2 swapped in storage (no longer "along the
 * axes": the general corner loop) must give the same nodes in the same
 * order and the same weights to round-off, for boxes up to 0.9 units wide
 * (wide ones too), either orientation, clamped at faces and wrapped on
 * periodic axes of few units; and the invariants hold. */
START_TEST(t_ugimp3_box_factorised)
{
  uint64_t st = 77;
  for (int per = 0; per < 8; per++) {
    mpm_mesh3 m = make_mesh3(3, 4, 2, per);
    for (int t = 0; t < 200; t++) {
      double r[9] = {0}, q[9] = {0}, xp[3];
      const double h[3] = {m.dx, m.dy, m.dz};
      for (int d = 0; d < 3; d++)
        r[4 * d] = (uni(&st) < 0.5 ? -1.0 : 1.0) * h[d] * (0.05 + 0.85 * uni(&st));
      random_point(&m, &st, r, xp);
      const int face = t % 4 == 0;             /* on a face: corners clamped (or wrapped) */
      if (face) {
        const double o[3] = {m.x0, m.y0, m.z0}, len[3] = {m.lx, m.ly, m.lz};
        const int d = t / 4 % 3;
        xp[d] = o[d] + (t / 8 % 2 ? 0.0 : len[d]);
      }
      memcpy(q, r + 3, 3 * sizeof *q);        /* q = [r2 r1 r3] */
      memcpy(q + 3, r, 3 * sizeof *q);
      memcpy(q + 6, r + 6, 3 * sizeof *q);
      int na[W], nb[W];
      double Sa[W], Sb[W], ga[W][3], gb[W][3];
      const int a = eval3(&mpm_shape3_ugimp, &m, xp, r, na, Sa, ga);
      const int b = eval3(&mpm_shape3_ugimp, &m, xp, q, nb, Sb, gb);
      ck_assert_int_gt(a, 0);
      ck_assert_int_eq(a, b);
      for (int k = 0; k < a; k++) {
        ck_assert_int_eq(na[k], nb[k]);
        ck_assert_double_eq_tol(Sa[k], Sb[k], 1e-15);
        for (int d = 0; d < 3; d++)
          ck_assert_double_eq_tol(ga[k][d] * h[d], gb[k][d] * h[d], 1e-14);
      }
      if (!face && per == 0)   /* clamping gives up linear reproduction, and so does a
                                  node reached from both sides of a short periodic axis */
        check_invariants(&m, &mpm_shape3_ugimp, xp, r);
    }
  }
}
END_TEST

START_TEST(t_ugimp3_nonfinite)
{
  for (int per = 0; per < 8; per += 7) {
    mpm_mesh3 m = make_mesh3(5, 4, 6, per);
    const double xp[3] = {m.x0 + 2.3 * m.dx, m.y0 + 1.6 * m.dy, m.z0 + 2.2 * m.dz};
    const double ok[9] = {0.2 * m.dx, 0, 0, 0, 0.2 * m.dy, 0, 0, 0, 0.2 * m.dz};
    int node[W];
    double S[W], g[W][3];
    for (const mpm_shape3_type *const *t = mpm_shape3_table; *t; t++)
      for (int d = 0; d < 3; d++) {
        double x[3] = {xp[0], xp[1], xp[2]};
        x[d] = NAN;
        ck_assert_int_eq(eval3(*t, &m, x, ok, node, S, g), -1);
        x[d] = -INFINITY;
        ck_assert_int_eq(eval3(*t, &m, x, ok, node, S, g), -1);
      }
    for (int v = 0; v < 2; v++) {
      const mpm_shape3_type *type = v ? &mpm_shape3_cpdi : &mpm_shape3_ugimp;
      for (int q = 0; q < 9; q++) {
        double r[9];
        memcpy(r, ok, sizeof r);
        r[q] = NAN;
        ck_assert_int_eq(eval3(type, &m, xp, r, node, S, g), -1);
        r[q] = INFINITY;
        ck_assert_int_eq(eval3(type, &m, xp, r, node, S, g), -1);
      }
      const double huge[9] = {1e200, 0, 0, 0, 1e200, 0, 0, 0, 1e200};   /* det overflows */
      ck_assert_int_eq(eval3(type, &m, xp, huge, node, S, g), -1);
      const double thin[9] = {1e200, 0, 0, 0, 1e200, 0, 0, 0, 1e-200};  /* w_c overflows */
      ck_assert_int_eq(eval3(type, &m, xp, thin, node, S, g), -1);
      const double flat[9] = {0.2 * m.dx, 0, 0, 0, 0.2 * m.dy, 0, 0.1 * m.dx, 0.1 * m.dy, 0};
      int nd[W];
      double Sd[W], gd[W][3];
      const int a = eval3(&mpm_shape3_delta, &m, xp, flat, nd, Sd, gd);
      ck_assert_int_eq(eval3(type, &m, xp, flat, node, S, g), a);
      for (int k = 0; k < a; k++) {
        ck_assert_int_eq(node[k], nd[k]);
        ck_assert(S[k] == Sd[k]);
      }
    }
  }
}
END_TEST

/* ------------------------------------------------------ convection */

/* r_k <- (I + dt L) r_k in 3D, step by step. A rigid spin about z,
 * L = [[0, -w, 0], [w, 0, 0], [0, 0, 0]]: on the xy part I + dt L is
 * sqrt(1 + (w dt)^2) times the rotation by atan(w dt), so after n steps the
 * xy part of r_k has turned by n atan(w dt) and grown by
 * (1 + (w dt)^2)^(n/2) (round-off 1e-13 over 1000 steps), z untouched. A
 * uniaxial stretch rate L = e e_z (x) e_z scales z by (1 + e dt)^n and
 * leaves x, y alone. The 2D call is the same arithmetic as D = 2. */
START_TEST(t_convect3)
{
  const double w = 3.0, dt = 1e-3, e = -2.0;
  const int n = 1000;
  const double r0[9] = {0.4, 0.1, 0.2, -0.05, 0.3, -0.1, 0.07, -0.02, 0.25};
  const double Ls[9] = {0, -w, 0, w, 0, 0, 0, 0, 0}, Le[9] = {0, 0, 0, 0, 0, 0, 0, 0, e};
  double a[9], b[9];
  memcpy(a, r0, sizeof a);
  memcpy(b, r0, sizeof b);
  for (int k = 0; k < n; k++) {
    mpm_shape_extent_convect_dim(3, a, Ls, dt);
    mpm_shape_extent_convect_dim(3, b, Le, dt);
  }
  const double th = n * atan(w * dt), gr = pow(1.0 + w * dt * w * dt, 0.5 * n);
  const double c = cos(th), sn = sin(th), sz = pow(1.0 + e * dt, n);
  for (int k = 0; k < 3; k++) {
    const double x = r0[3 * k], y = r0[3 * k + 1], z = r0[3 * k + 2];
    ck_assert_double_eq_tol(a[3 * k], gr * (c * x - sn * y), 1e-13);
    ck_assert_double_eq_tol(a[3 * k + 1], gr * (sn * x + c * y), 1e-13);
    ck_assert_double_eq(a[3 * k + 2], z);
    ck_assert_double_eq(b[3 * k], x);
    ck_assert_double_eq(b[3 * k + 1], y);
    ck_assert_double_eq_tol(b[3 * k + 2], sz * z, 1e-13);
  }
  uint64_t s = 5;
  for (int t = 0; t < 1000; t++) {
    double r2[4], L2[4], q[4];
    for (int i = 0; i < 4; i++) {
      r2[i] = uni(&s) - 0.5;
      L2[i] = 10.0 * (uni(&s) - 0.5);
      q[i] = r2[i];
    }
    mpm_shape_extent_convect(&q[0], &q[1], &q[2], &q[3], L2[0], L2[1], L2[2], L2[3], 1e-3);
    const double want[4] = {r2[0] + 1e-3 * (L2[0] * r2[0] + L2[1] * r2[1]),
                            r2[1] + 1e-3 * (L2[2] * r2[0] + L2[3] * r2[1]),
                            r2[2] + 1e-3 * (L2[0] * r2[2] + L2[1] * r2[3]),
                            r2[3] + 1e-3 * (L2[2] * r2[2] + L2[3] * r2[3])};
    for (int i = 0; i < 4; i++)
      ck_assert(q[i] == want[i]);                 /* the former 2D expressions, bit for bit */
  }
}
END_TEST

/* ------------------------------------------------------------ registry */

START_TEST(t_registry3)
{
  ck_assert_ptr_eq(mpm_shape3_lookup("delta"), &mpm_shape3_delta);
  ck_assert_ptr_eq(mpm_shape3_lookup("ugimp"), &mpm_shape3_ugimp);
  ck_assert_ptr_eq(mpm_shape3_lookup("cpdi"), &mpm_shape3_cpdi);
  ck_assert_ptr_null(mpm_shape3_lookup("bspline"));
  ck_assert_ptr_null(mpm_shape3_lookup(""));
  ck_assert_ptr_null(mpm_shape3_lookup(NULL));
  ck_assert_int_eq(mpm_shape3_delta.at_point, 1);
  ck_assert_int_eq(mpm_shape3_ugimp.at_point, 0);
  ck_assert_int_eq(mpm_shape3_ugimp.convect, 0);
  ck_assert_int_eq(mpm_shape3_cpdi.convect, 1);
  int n = 0;
  for (const mpm_shape3_type *const *t = mpm_shape3_table; *t; t++, n++) {
    ck_assert_ptr_nonnull((*t)->description);
    ck_assert_ptr_nonnull((*t)->eval);
    ck_assert_ptr_nonnull((*t)->span);
    ck_assert_ptr_eq(mpm_shape3_lookup((*t)->name), *t);
    ck_assert_ptr_nonnull(mpm_shape_lookup((*t)->name));  /* the 2D names */
  }
  ck_assert_int_eq(n, 3);
  /* spans: delta 8 nodes in the unit; half-unit extents 3 x 3 x 3, one unit
   * beyond; 1.2 units: 5 nodes an axis, capped at 64, two units beyond */
  mpm_mesh3 m = make_mesh3(14, 14, 14, 0);
  const double r[2][9] = {{0.25 * m.dx, 0, 0, 0, 0.25 * m.dy, 0, 0, 0, 0.25 * m.dz},
                          {1.2 * m.dx, 0, 0, 0, 1.2 * m.dy, 0, 0, 0, 1.2 * m.dz}};
  int w, reach;
  mpm_shape3_delta.span(&m, 2, &r[0][0], &w, &reach);
  ck_assert_int_eq(w, 8);
  ck_assert_int_eq(reach, 0);
  mpm_shape3_ugimp.span(&m, 1, &r[0][0], &w, &reach);
  ck_assert_int_eq(w, 27);
  ck_assert_int_eq(reach, 1);
  mpm_shape3_cpdi.span(&m, 2, &r[0][0], &w, &reach);
  ck_assert_int_eq(w, 64);
  ck_assert_int_eq(reach, 2);
}
END_TEST

int main(void)
{
  Suite *s = suite_create("shape3");
  TCase *tc = tcase_create("shape3");
  tcase_set_timeout(tc, 120);
  tcase_add_test(tc, t_mesh3_setup);
  tcase_add_test(tc, t_mesh3_nodes);
  tcase_add_test(tc, t_mesh3_locate);
  tcase_add_test(tc, t_mesh3_basis);
  tcase_add_test(tc, t_corner_rule);
  tcase_add_test(tc, t_invariants_delta3);
  tcase_add_test(tc, t_invariants_ugimp3);
  tcase_add_test(tc, t_invariants_ugimp3_wide);
  tcase_add_test(tc, t_invariants_cpdi3);
  tcase_add_test(tc, t_ugimp3_box_is_delta);
  tcase_add_test(tc, t_ugimp3_rotated_hand);
  tcase_add_test(tc, t_ugimp3_on_node);
  tcase_add_test(tc, t_ugimp3_clamped);
  tcase_add_test(tc, t_ugimp3_periodic);
  tcase_add_test(tc, t_ugimp3_box_factorised);
  tcase_add_test(tc, t_ugimp3_nonfinite);
  tcase_add_test(tc, t_convect3);
  tcase_add_test(tc, t_registry3);
  suite_add_tcase(s, tc);
  SRunner *sr = srunner_create(s);
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf ? EXIT_FAILURE : EXIT_SUCCESS;
}
