/* test_box_shape.c: the shape variants on a mesh of boxes (dim = 3; the
 * plane's are in test_shape.c), MODEL.md section 3.
 *
 * The kernel invariants of VERIFICATION.md case V0 for delta, ugimp and
 * cpdi on meshes with every combination of periodic axes, at random points
 * with random parallelepiped extents (rotated, sheared, both orientations,
 * wide ones with corners in non-adjacent units),
 *   sum_i S_ip = 1,  sum_i gradS_ip = 0,  sum_i S_ip x_i = x_p,
 *   sum_i x_i (x) gradS_ip = I,
 * node ids valid and distinct, the counts within the variant's span (its
 * width, and its reach along the last axis, the one the step bands the
 * points by), every node within the units of the point's corners; and
 * hand values: a box extent inside one unit (the corner rule then equals
 * the delta weights: the trilinear N is linear along each axis, and the
 * sign patterns of the corners are independent), a rotated extent (it does
 * not: S_a = N_a(x_p) + the pair terms below), a point on a node, clamped
 * corners, periodic wrap and merged nodes, points outside, non-finite input;
 * the corner geometry against the 2D formula of MODEL.md (D = 2, exactly)
 * and the extent convection against closed forms.
 * The factorised (separable) weights of an extent along the axes: the
 * stencil of a point store (mpm_shape_stencil_compute, the batched path)
 * is the per-point rule bit for bit, and both are the general corner rule
 * to round-off, at faces, across periodic seams, on nodes and unit edges;
 * on periodic axes of one or two units (aliased nodes, merged) the weights
 * still sum to 1 with gradients summing to 0, and are the wider mesh's
 * weights summed over the nodes that alias.
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
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "box.h"
#include "core/points.h"
#include "mesh/mesh.h"
#include "shape/corners.h"
#include "shape/shape.h"

#define TOL 1e-12
#define W MPM_STENCIL_W

/* splitmix64 in [0, 1); state passed by the caller. */
static double uni(uint64_t *s)
{
  uint64_t z = (*s += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  z ^= z >> 31;
  return (double)(z >> 11) * 0x1.0p-53;
}

static double det3(const double r[9])
{
  return r[0] * (r[4] * r[8] - r[7] * r[5]) - r[3] * (r[1] * r[8] - r[7] * r[2]) +
         r[6] * (r[1] * r[5] - r[4] * r[2]);
}

/* Random extent: |r_k| in [lo, hi] min(dx, dy, dz), directions uniform on
 * the sphere, |det R| >= 0.25 |r1| |r2| |r3| (not nearly flat), r3 flipped
 * half the time so both orientations come often. */
static void random_extent(const mpm_mesh *m, uint64_t *s, double lo, double hi, double r[9])
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
static void random_point(const mpm_mesh *m, uint64_t *s, const double r[9], double xp[3])
{
  const double o[3] = {m->x0, m->y0, m->z0}, len[3] = {m->lx, m->ly, m->lz};
  const double h[3] = {m->dx, m->dy, m->dz};
  const int per[3] = {m->periodic_x, m->periodic_y, m->periodic_z};
  for (int d = 0; d < 3; d++) {
    const double margin = fabs(r[d]) + fabs(r[3 + d]) + fabs(r[6 + d]);
    xp[d] = random_coord(s, o[d], len[d], h[d], per[d], margin);
  }
}

/* A 3D point store of n points at the origin of m with the extents
 * r[9 p ...] (r[9 p + 3 k + d] = component d of r_{k+1} of point p). */
static mpm_points *store_of(const mpm_mesh *m, int n, const double *r)
{
  mpm_points *P = mpm_points_alloc_dim((size_t)n, 3);
  ck_assert_ptr_nonnull(P);
  for (int p = 0; p < n; p++) {
    size_t i;
    ck_assert_int_eq(mpm_points_push(P, &i), MPM_OK);
    for (int d = 0; d < 3; d++)
      P->pos[d][i] = m->o[d];
    for (int k = 0; k < 3; k++)
      for (int d = 0; d < 3; d++)
        P->ext[k][d][i] = r[9 * p + 3 * k + d];
  }
  return P;
}

/* The span of type for the n points of extents r (store_of). */
static void span_of(const mpm_shape_type *type, const mpm_mesh *m, int n, const double *r,
                    int *width, int *reach)
{
  mpm_points *P = store_of(m, n, r);
  type->span(m, P, width, reach);
  mpm_points_free(P);
}

/* Evaluate type at (xp, r): ids valid and distinct, the count within the
 * span (width and reach along each axis), and the four invariants; returns
 * the node count. */
static int check_invariants(const mpm_mesh *m, const mpm_shape_type *type, const double xp[3],
                            const double r[9])
{
  int node[W];
  double S[W], gx[W], gy[W], gz[W];
  double *const dS[3] = {gx, gy, gz};
  const int n = type->eval(m, xp, r, node, S, dS);
  int width, reach;
  span_of(type, m, 1, r, &width, &reach);
  ck_assert_int_ge(n, 8);
  ck_assert_int_le(n, width);
  ck_assert_int_le(width, W);
  const double o[3] = {m->x0, m->y0, m->z0}, h[3] = {m->dx, m->dy, m->dz};
  double s0 = 0, g[3] = {0, 0, 0}, mx[3] = {0, 0, 0}, I[3][3] = {{0}};
  /* the node checks counted, then asserted once (Check records every
   * assertion it passes) */
  int bad_id = 0, twice = 0, beyond = 0;
  for (int k = 0; k < n; k++) {
    bad_id += node[k] < 0 || node[k] >= m->nnodes;
    for (int l = 0; l < k; l++)
      twice += node[k] == node[l];              /* merged: each node once */
    double xi[3];
    box_node_near(m, node[k], xp, xi);
    const double gk[3] = {gx[k], gy[k], gz[k]};
    s0 += S[k];
    for (int a = 0; a < 3; a++) {
      /* node index along a: within the units of the corners, which lie
       * within h_a = sum_k |r_ka| of the point (a 1e-9 unit of slack for
       * round-off); along the last axis (the band axis, whose reach the
       * span gives) -reach .. 1 + reach from the point's unit */
      const double li = round((xi[a] - o[a]) / h[a]), ui = floor((xp[a] - o[a]) / h[a]);
      const double ha = fabs(r[a]) + fabs(r[3 + a]) + fabs(r[6 + a]);
      beyond += li < floor((xp[a] - ha - o[a]) / h[a] - 1e-9) ||
                li > floor((xp[a] + ha - o[a]) / h[a] + 1e-9) + 1;
      if (a == 2)
        beyond += li - ui < -reach || li - ui > 1 + reach;
      g[a] += gk[a];
      mx[a] += S[k] * xi[a];
      for (int b = 0; b < 3; b++)
        I[a][b] += xi[a] * gk[b];
    }
  }
  ck_assert_msg(!bad_id && !twice && !beyond, "%s at (%g, %g, %g): %d node ids outside the mesh, "
                "%d listed twice, %d beyond the corners' units or the span", type->name, xp[0],
                xp[1], xp[2], bad_id, twice, beyond);
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
static int invariants_on(const mpm_shape_type *type, double rlo, double rhi, int n,
                         int trials, uint64_t seed)
{
  uint64_t s = seed;
  int neg = 0;
  for (int per = 0; per < 8; per++) {
    mpm_mesh m = make_box(n, n + 1, n - 1, per);
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

/* ------------------------------------------------------- corner rule */

/* D = 2: the offsets and weights are the 2D formula of MODEL.md, value for
 * value (A = 4 det R; corner 1 w = (1/A)(r1y - r2y, r2x - r1x), corner 2
 * (1/A)(r1y + r2y, -r1x - r2x), corners 3, 4 the negatives). D = 3:
 * sum_c w_c = 0 and sum_c w_c (x) (x_c - x_p) = I, and the corners are the
 * signs of the header's order. */
START_TEST(t_box_corner_rule)
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
  mpm_mesh m = make_box(4, 4, 4, 0);
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

START_TEST(t_box_invariants_delta)
{
  invariants_on(&mpm_shape_delta, 0.1, 0.5, 6, 150, 0x5EEDULL);
}
END_TEST

START_TEST(t_box_invariants_ugimp)
{
  const int neg = invariants_on(&mpm_shape_ugimp, 0.1, 0.5, 6, 300, 0xC0FFEEULL);
  ck_assert_int_gt(neg, 600);                     /* both orientations, about half each */
  ck_assert_int_lt(neg, 1800);
}
END_TEST

/* Extents up to 1.5 units: corners up to 4.5 units away, in non-adjacent
 * units: up to 64 distinct nodes, listed node by node. */
START_TEST(t_box_invariants_ugimp_wide)
{
  invariants_on(&mpm_shape_ugimp, 0.5, 1.5, 14, 150, 0xBADF00DULL);
  mpm_mesh m = make_box(14, 14, 14, 0);
  const double r[9] = {1.2 * m.dx, 0, 0, 0, 1.2 * m.dy, 0, 0, 0, 1.2 * m.dz};
  const double xp[3] = {m.x0 + 7.5 * m.dx, m.y0 + 7.5 * m.dy, m.z0 + 7.5 * m.dz};
  ck_assert_int_eq(check_invariants(&m, &mpm_shape_ugimp, xp, r), 64);  /* 8 separate units */
}
END_TEST

/* CPDI1 extents as the deformation makes them: sheared, stretched to 1.5
 * units or squeezed to 0.1. */
START_TEST(t_box_invariants_cpdi)
{
  invariants_on(&mpm_shape_cpdi, 0.1, 1.5, 14, 150, 0xFEEDULL);
}
END_TEST

/* ------------------------------------------------------------ by hand */

/* Weights of type at xp: the count; node, S and gradient out. */
static int eval3(const mpm_shape_type *type, const mpm_mesh *m, const double xp[3],
                 const double r[9], int *node, double *S, double (*g)[3])
{
  double gx[W], gy[W], gz[W];
  double *const dS[3] = {gx, gy, gz};
  const int n = type->eval(m, xp, r, node, S, dS);
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
START_TEST(t_box_ugimp_box_is_delta)
{
  mpm_mesh m = make_box(5, 4, 6, 2);
  const double xp[3] = {m.x0 + 2.4 * m.dx, m.y0 + 1.55 * m.dy, m.z0 + 3.3 * m.dz};
  const double boxes[2][9] = {{0.2 * m.dx, 0, 0, 0, 0.15 * m.dy, 0, 0, 0, 0.25 * m.dz},
                              {0.2 * m.dx, 0, 0, 0, -0.3 * m.dy, 0, 0, 0, 0.1 * m.dz}};
  for (int q = 0; q < 2; q++) {
    int na[W], nb[W];
    double Sa[W], Sb[W], ga[W][3], gb[W][3];
    const int a = eval3(&mpm_shape_delta, &m, xp, boxes[q], na, Sa, ga);
    const int b = eval3(&mpm_shape_ugimp, &m, xp, boxes[q], nb, Sb, gb);
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
START_TEST(t_box_ugimp_rotated_hand)
{
  mpm_mesh m = make_box(5, 4, 6, 0);
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
  ck_assert_int_eq(eval3(&mpm_shape_ugimp, &m, xp, r, node, S, g), 8);
  int corner[8];
  const int cu[3] = {2, 1, 3};
  mpm_mesh_unit_corners(&m, cu, corner);
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
START_TEST(t_box_ugimp_on_node)
{
  mpm_mesh m = make_box(5, 4, 6, 0);
  const double h = 0.03;
  const double r[9] = {h, 0, 0, 0, -h, 0, 0, 0, h};  /* det < 0: the same weights */
  double xp[3];
  mpm_mesh_node_pos(&m, 2, 2, 2, xp);
  int node[W];
  double S[W], g[W][3];
  ck_assert_int_eq(eval3(&mpm_shape_ugimp, &m, xp, r, node, S, g), 27);
  const double ux = h / m.dx, uy = h / m.dy, uz = h / m.dz;
  int k = find(node, 27, mpm_mesh_node(&m, 2, 2, 2));
  ck_assert_int_lt(k, 27);
  ck_assert_double_eq_tol(S[k], (1 - ux) * (1 - uy) * (1 - uz), TOL);
  for (int d = 0; d < 3; d++)
    ck_assert_double_eq_tol(g[k][d], 0.0, TOL);
  k = find(node, 27, mpm_mesh_node(&m, 3, 3, 3));
  ck_assert_int_lt(k, 27);
  ck_assert_double_eq_tol(S[k], ux * uy * uz / 8, TOL);
  k = find(node, 27, mpm_mesh_node(&m, 3, 2, 2));
  ck_assert_int_lt(k, 27);
  const double N = ux * (1 - uy) * (1 - uz);
  ck_assert_double_eq_tol(S[k], N / 2, TOL);
  ck_assert_double_eq_tol(g[k][0], N / (2 * h), TOL);
  ck_assert_double_eq_tol(g[k][1], 0.0, TOL);
  ck_assert_double_eq_tol(g[k][2], 0.0, TOL);
  /* listed layer by layer, row by row: node (1, 1, 1) first, (3, 3, 3) last */
  ck_assert_int_eq(node[0], mpm_mesh_node(&m, 1, 1, 1));
  ck_assert_int_eq(node[26], mpm_mesh_node(&m, 3, 3, 3));
}
END_TEST

/* Corners beyond a non-periodic face are clamped onto it. Point at
 * (x0 + 0.1 dx, y0 + 2.5 dy, z0 + 1.5 dz), r1 = (0.4 dx, 0, 0),
 * r2 = (0, 0.25 dy, 0), r3 = (0, 0, 0.25 dz): the x corners go to x0
 * (clamped from x0 - 0.3 dx) and x0 + 0.5 dx, so node column 0 takes
 * (1 + 0.5)/2 = 0.75 and column 1 0.25; rows 2, 3 and layers 1, 2 take 1/2
 * each. Centres on faces are inside, just beyond them outside. */
START_TEST(t_box_ugimp_clamped)
{
  mpm_mesh m = make_box(5, 4, 6, 0);
  const double r[9] = {0.4 * m.dx, 0, 0, 0, 0.25 * m.dy, 0, 0, 0, 0.25 * m.dz};
  const double xp[3] = {m.x0 + 0.1 * m.dx, m.y0 + 2.5 * m.dy, m.z0 + 1.5 * m.dz};
  for (int v = 0; v < 2; v++) {
    const mpm_shape_type *type = v ? &mpm_shape_cpdi : &mpm_shape_ugimp;
    int node[W];
    double S[W], g[W][3];
    const int n = eval3(type, &m, xp, r, node, S, g);
    ck_assert_int_eq(n, 8);
    double s0 = 0, gs[3] = {0, 0, 0};
    for (int k = 0; k < n; k++) {
      int ijk[3];
      box_node_ijk(&m, node[k], ijk);
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
  for (const mpm_shape_type *const *t = mpm_shape_table; *t; t++) {
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
START_TEST(t_box_ugimp_periodic)
{
  mpm_mesh m = make_box(5, 4, 6, 1);
  const double r[9] = {0.4 * m.dx, 0, 0, 0, 0.25 * m.dy, 0, 0, 0, 0.25 * m.dz};
  const double xp[3] = {m.x0 + 0.1 * m.dx, m.y0 + 2.5 * m.dy, m.z0 + 1.5 * m.dz};
  int node[W], node2[W];
  double S[W], g[W][3], S2[W], g2[W][3];
  const int n = eval3(&mpm_shape_ugimp, &m, xp, r, node, S, g);
  ck_assert_int_eq(n, 12);                        /* columns nx-1, 0, 1 x 2 rows x 2 layers */
  int last = 0;
  for (int k = 0; k < n; k++) {
    int ijk[3];
    box_node_ijk(&m, node[k], ijk);
    if (ijk[0] == m.nx - 1) {
      ck_assert_double_eq_tol(S[k], 0.15 * 0.25, TOL);
      last++;
    }
  }
  ck_assert_int_eq(last, 4);
  const double xq[3] = {xp[0] + m.lx, xp[1], xp[2]};
  ck_assert_int_eq(eval3(&mpm_shape_ugimp, &m, xq, r, node2, S2, g2), n);
  for (int k = 0; k < n; k++) {
    ck_assert_int_eq(node2[k], node[k]);
    ck_assert_double_eq_tol(S2[k], S[k], TOL);
    for (int d = 0; d < 3; d++)
      ck_assert_double_eq_tol(g2[k][d], g[k][d], TOL);
  }
  /* merging: z periodic on 2 units, an extent of 0.6 units along z (the
   * block: 3 node layers of which two are one stored layer) and one also
   * 1.6 units along x (corners 4 units apart: node by node) */
  mpm_mesh t = make_box(5, 4, 2, 4);
  const double rz[2][9] = {{0.3 * t.dx, 0, 0, 0, 0.3 * t.dy, 0, 0.1 * t.dx, 0, 0.6 * t.dz},
                           {1.6 * t.dx, 0, 0, 0, 0.3 * t.dy, 0, 0.1 * t.dx, 0, 0.6 * t.dz}};
  const double xt[3] = {t.x0 + 2.5 * t.dx, t.y0 + 1.5 * t.dy, t.z0 + 0.3 * t.dz};
  for (int q = 0; q < 2; q++) {
    const int c = eval3(&mpm_shape_ugimp, &t, xt, rz[q], node, S, g);
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

/* An extent along the axes takes the factorised rule
 * (mpm_shape_in_separable): the same extent with r1 and r2 swapped in
 * storage (off-diagonal in storage: the general corner loop) must give the
 * same nodes in the same order and the same weights to round-off, for
 * boxes up to 0.9 units wide (wide ones too), either orientation, clamped
 * at faces and wrapped on periodic axes of few units; and the invariants
 * hold. */
START_TEST(t_box_ugimp_box_factorised)
{
  uint64_t st = 77;
  for (int per = 0; per < 8; per++) {
    mpm_mesh m = make_box(3, 4, 2, per);
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
      const int a = eval3(&mpm_shape_ugimp, &m, xp, r, na, Sa, ga);
      const int b = eval3(&mpm_shape_ugimp, &m, xp, q, nb, Sb, gb);
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
        check_invariants(&m, &mpm_shape_ugimp, xp, r);
    }
  }
}
END_TEST

/* Non-finite points and extents are reported as outside (-1), not used; a
 * corner geometry that overflows too; a flat extent (det R = 0) takes the
 * delta weights. */
START_TEST(t_box_ugimp_nonfinite)
{
  for (int per = 0; per < 8; per += 7) {
    mpm_mesh m = make_box(5, 4, 6, per);
    const double xp[3] = {m.x0 + 2.3 * m.dx, m.y0 + 1.6 * m.dy, m.z0 + 2.2 * m.dz};
    const double ok[9] = {0.2 * m.dx, 0, 0, 0, 0.2 * m.dy, 0, 0, 0, 0.2 * m.dz};
    int node[W];
    double S[W], g[W][3];
    for (const mpm_shape_type *const *t = mpm_shape_table; *t; t++)
      for (int d = 0; d < 3; d++) {
        double x[3] = {xp[0], xp[1], xp[2]};
        x[d] = NAN;
        ck_assert_int_eq(eval3(*t, &m, x, ok, node, S, g), -1);
        x[d] = -INFINITY;
        ck_assert_int_eq(eval3(*t, &m, x, ok, node, S, g), -1);
      }
    for (int v = 0; v < 2; v++) {
      const mpm_shape_type *type = v ? &mpm_shape_cpdi : &mpm_shape_ugimp;
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
      const int a = eval3(&mpm_shape_delta, &m, xp, flat, nd, Sd, gd);
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
 * leaves x, y alone. D = 2 is the plane's closed form
 * r_k + dt (L r_k), the same operations in the same order, bit for bit. */
START_TEST(t_box_convect)
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
    mpm_shape_extent_convect_dim(2, q, L2, 1e-3);
    const double want[4] = {r2[0] + 1e-3 * (L2[0] * r2[0] + L2[1] * r2[1]),
                            r2[1] + 1e-3 * (L2[2] * r2[0] + L2[3] * r2[1]),
                            r2[2] + 1e-3 * (L2[0] * r2[2] + L2[1] * r2[3]),
                            r2[3] + 1e-3 * (L2[2] * r2[2] + L2[3] * r2[3])};
    for (int i = 0; i < 4; i++)
      ck_assert(q[i] == want[i]);                 /* the plane's closed form, bit for bit */
  }
}
END_TEST

/* ------------------------------------------------------------ registry */

START_TEST(t_box_registry)
{
  ck_assert_ptr_eq(mpm_shape_lookup("delta"), &mpm_shape_delta);
  ck_assert_ptr_eq(mpm_shape_lookup("ugimp"), &mpm_shape_ugimp);
  ck_assert_ptr_eq(mpm_shape_lookup("cpdi"), &mpm_shape_cpdi);
  ck_assert_ptr_null(mpm_shape_lookup("bspline"));
  ck_assert_ptr_null(mpm_shape_lookup(""));
  ck_assert_ptr_null(mpm_shape_lookup(NULL));
  ck_assert_int_eq(mpm_shape_delta.at_point, 1);
  ck_assert_int_eq(mpm_shape_ugimp.at_point, 0);
  ck_assert_int_eq(mpm_shape_ugimp.convect, 0);
  ck_assert_int_eq(mpm_shape_cpdi.convect, 1);
  ck_assert_int_eq(mpm_shape_ugimp.separable, 1);  /* factorised on boxes */
  ck_assert_int_eq(mpm_shape_cpdi.separable, 0);   /* a convected extent leaves the axes */
  ck_assert_int_eq(mpm_shape_delta.separable, 0);
  int n = 0;
  for (const mpm_shape_type *const *t = mpm_shape_table; *t; t++, n++) {
    ck_assert_ptr_nonnull((*t)->description);
    ck_assert_ptr_nonnull((*t)->eval);
    ck_assert_ptr_nonnull((*t)->span);
    ck_assert_ptr_eq(mpm_shape_lookup((*t)->name), *t);
  }
  ck_assert_int_eq(n, 3);
  /* spans: delta 8 nodes in the unit; half-unit extents 3 x 3 x 3, one unit
   * beyond; 1.2 units: 5 nodes an axis, capped at 64, two units beyond */
  mpm_mesh m = make_box(14, 14, 14, 0);
  const double r[2][9] = {{0.25 * m.dx, 0, 0, 0, 0.25 * m.dy, 0, 0, 0, 0.25 * m.dz},
                          {1.2 * m.dx, 0, 0, 0, 1.2 * m.dy, 0, 0, 0, 1.2 * m.dz}};
  int w, reach;
  span_of(&mpm_shape_delta, &m, 2, &r[0][0], &w, &reach);
  ck_assert_int_eq(w, 8);
  ck_assert_int_eq(reach, 0);
  span_of(&mpm_shape_ugimp, &m, 1, &r[0][0], &w, &reach);
  ck_assert_int_eq(w, 27);
  ck_assert_int_eq(reach, 1);
  span_of(&mpm_shape_cpdi, &m, 2, &r[0][0], &w, &reach);
  ck_assert_int_eq(w, 64);
  ck_assert_int_eq(reach, 2);
}
END_TEST

/* ------------------------------------------------- the factorised rule */

/* A mesh of boxes of n[d] units along axis d, periodic axes from the bits
 * of per. exact: origin 0 and unit sizes 1/8, 1/4, 1/16 m, binary fractions,
 * so that nodes, unit edges and the corners of fill extents are exact
 * numbers; else the offset origin and unequal sizes of make_box. */
static mpm_mesh sep_mesh(const int n[3], int per, int exact)
{
  mpm_mesh m = make_box(n[0], n[1], n[2], per);
  if (exact) {
    const double h[3] = {0.125, 0.25, 0.0625};
    for (int d = 0; d < 3; d++) {
      m.o[d] = 0.0;
      m.h[d] = h[d];
    }
    mpm_err err = {0};
    ck_assert_msg(mpm_mesh_setup(&m, &err) == MPM_OK, "%s", err.msg);
  }
  return m;
}

/* One coordinate along axis d of m for a point of half-width hw, of kind
 * k: 0 anywhere (on a periodic axis also up to a unit beyond either face),
 * 1 within half a unit of a face (its corners clamped, or across the seam),
 * 2 on a node, 3 a corner on a node plane (a unit edge), 4 a sub-cell
 * centre of a fill of ppu points a unit (corners on sub-cell edges). */
static double sep_coord(const mpm_mesh *m, int d, int k, double hw, int ppu, uint64_t *s)
{
  const double o = m->o[d], len = m->len[d], h = m->h[d];
  const int n = m->n[d], per = m->periodic[d];
  const int i = (int)((n + 1) * uni(s)) % (n + 1);         /* a node 0 .. n */
  double x;
  switch (k) {
  case 0:
    return per ? o - h + (len + 2.0 * h) * uni(s) : o + len * uni(s);
  case 1:
    x = 0.5 * h * uni(s);
    return uni(s) < 0.5 ? o + x : o + len - x;
  case 2:
    return o + i * h;
  case 3:
    x = o + i * h + (uni(s) < 0.5 ? hw : -hw);
    if (!per && x < o)
      x += 2.0 * hw;
    if (!per && x > o + len)
      x -= 2.0 * hw;
    return x;
  default: {
    const int u = (int)(n * uni(s)) % n, q = (int)(ppu * uni(s)) % ppu;
    return o + (u + (q + 0.5) / ppu) * h;
  }
  }
}

/* Point p of store P (extent along the axes) against the stencil st of the
 * store: the stencil's factorised weights are those of the per-point rule
 * mpm_shape_in_separable bit for bit (nodes, A and B along each axis, the
 * count, the centre's unit along z); and the weights they make are those of
 * the general corner rule. The two sum the same corner values of the hat
 * functions in different groupings: the factorised S = A_x (A_y A_z) with
 * A = (phi(-) + phi(+))/2, the general S = sum_c N(x_c)/8 over 8 corners
 * with N a product of three factors, each term <= 1/8; a handful of
 * roundings each, so |S - S'| <= ~17 eps = 3.8e-15. The gradients times the
 * half-width h_d: B h_d = (phi(+) - phi(-))/2 <= 1/2 against
 * sum_c (w_c h_d) N(x_c), |w_c h_d| = 1/8, with the cofactor rule's few
 * roundings of w_c: <= ~20 eps = 4.4e-15. The factorised rule also puts a
 * corner within MPM_SHAPE_SNAP (1e-12) units of a node on it, which moves
 * each hat value by at most that, so S by at most 1e-12 and B h_d by at
 * most 1e-12 (a corner's share of either is at most 1/2 of its hat value's
 * change, and the two corners of an axis add), and leaves out the end nodes
 * whose weights became 0: a node of the general rule's list missing from
 * the factorised one must then weigh at most that. 2e-12 bounds both, while
 * a wrong hat value or corner is off by 1e-3 or more. */
static void sep_compare(const mpm_mesh *m, const mpm_points *P, const mpm_shape_stencil *st,
                        size_t p)
{
  /* one assertion per point (Check records every assertion it passes) */
  double r[9], h[3];
  mpm_shape_point_extent(P, 3, p, r);
  const double x[3] = {P->x[p], P->y[p], P->z[p]};
  int c[3];
  double l[3];
  mpm_shape_axes ax;
  const int setup = mpm_shape_in_axes_extent(3, r, h) && !mpm_mesh_locate(m, x, c, l) &&
                    mpm_shape_in_separable(m, x, c, h, &ax) == 0;
  ck_assert_msg(setup, "point %zu: no factorised weights", p);
  const mpm_shape_axes *b = &st->axes[p];
  int same = st->count[p] == ax.n[0] * ax.n[1] * ax.n[2] && st->row[p] == c[2];
  for (int d = 0; d < 3; d++) {
    same &= b->n[d] == ax.n[d];
    for (int k = 0; same && k < ax.n[d]; k++)
      same &= b->idx[d][k] == ax.idx[d][k] &&
              memcmp(&b->A[d][k], &ax.A[d][k], sizeof(double)) == 0 &&
              memcmp(&b->B[d][k], &ax.B[d][k], sizeof(double)) == 0;
  }
  ck_assert_msg(same, "point %zu at (%.17g, %.17g, %.17g): the stencil's factorised weights "
                "are not the per-point rule's", p, x[0], x[1], x[2]);
  int ns[W], ng[W];
  double Ss[W], Sg[W], gs[3][W], gg[3][W];
  double *const dss[3] = {gs[0], gs[1], gs[2]}, *const dsg[3] = {gg[0], gg[1], gg[2]};
  const int cs = mpm_shape_stencil_list(st, m, p, ns, Ss, dss);
  const int cg = mpm_shape_in_corner_general(m, x, r, ng, Sg, dsg);
  double worst = 0.0;
  int found = cs == st->count[p] && cs <= cg, listed[W] = {0};
  for (int k = 0; found && k < cs; k++) {
    const int q = find(ng, cg, ns[k]);
    found = q < cg;
    if (!found)
      break;
    listed[q] = 1;
    worst = fmax(worst, fabs(Ss[k] - Sg[q]));
    for (int d = 0; d < 3; d++)
      worst = fmax(worst, fabs(gs[d][k] - gg[d][q]) * h[d]);
  }
  ck_assert_msg(found, "point %zu: %d nodes factorised, %d by the general rule, not among them",
                p, cs, cg);
  for (int q = 0; q < cg; q++)                     /* left out: weights of the snap's size */
    if (!listed[q]) {
      worst = fmax(worst, fabs(Sg[q]));
      for (int d = 0; d < 3; d++)
        worst = fmax(worst, fabs(gg[d][q]) * h[d]);
    }
  ck_assert_msg(worst <= 2e-12, "point %zu at (%.17g, %.17g, %.17g): factorised and general "
                "weights differ by %g", p, x[0], x[1], x[2], worst);
}

/* A fill of 1 or 2 points a unit side puts every corner of a uGIMP extent
 * on a node or a unit's middle plane, up to the round-off of the point's
 * position (a unit size of 0.13 m and an origin of -0.4 m are not binary
 * fractions): with the corners within MPM_SHAPE_SNAP of a node put on it
 * and end nodes of weight 0 left out, such a point weighs exactly the 2
 * nodes a side it touches, 8 in all, wherever it lies (without: 27 or 64
 * with weights of 1e-17 at the ends, which point-to-grid and the gather
 * would visit for nothing). */
START_TEST(t_separable_fill_nodes)
{
  const mpm_mesh m = make_box(7, 6, 5, 5);
  for (int ppu = 1; ppu <= 2; ppu++) {
    mpm_points *P = mpm_points_alloc_dim(0, 3);
    ck_assert_ptr_nonnull(P);
    for (int k = 0; k < m.nz * ppu; k++)
      for (int j = 0; j < m.ny * ppu; j++)
        for (int i = 0; i < m.nx * ppu; i++) {
          size_t q;
          ck_assert_int_eq(mpm_points_push(P, &q), MPM_OK);
          const int at[3] = {i, j, k};
          for (int d = 0; d < 3; d++) {
            P->pos[d][q] = m.o[d] + (at[d] + 0.5) * m.h[d] / ppu;
            P->ext[d][d][q] = 0.5 * m.h[d] / ppu;
          }
        }
    mpm_shape_stencil *st = mpm_shape_stencil_alloc(0);
    ck_assert_ptr_nonnull(st);
    mpm_err err = {0};
    ck_assert_int_eq(mpm_shape_stencil_compute(st, &mpm_shape_ugimp, &m, P, 0.0, &err), MPM_OK);
    ck_assert_int_eq(st->sep, 1);
    long other = 0;
    for (size_t p = 0; p < P->n; p++)
      other += st->count[p] != 8;
    ck_assert_msg(other == 0, "ppu %d: %ld of %zu points weigh other than 8 nodes", ppu, other,
                  P->n);
    mpm_shape_stencil_free(st);
    mpm_points_free(P);
  }
}
END_TEST

/* The stencil of a store of boxes (mpm_shape_stencil_compute: the
 * factorised form, each axis of a batch of points in one loop) against the
 * per-point rule and the general rule (sep_compare), for every combination
 * of periodic axes on axes of 3, 4 and 8 units, exact and inexact unit
 * sizes, the extents of fills of 1, 2 and 3 points a unit (half-widths
 * 1/2, 1/4, 1/6 of a unit, either sign), at points of every kind of
 * sep_coord. Counted: corners clamped at a non-periodic face and corner
 * pairs across a periodic seam, so that the test covers them. */
START_TEST(t_separable_batch_is_per_point)
{
  static const int dims[3][3] = {{3, 4, 8}, {8, 3, 4}, {4, 8, 3}};
  uint64_t s = 0x5E9A11ULL;
  long clamped = 0, seam = 0, total = 0;
  for (int exact = 0; exact < 2; exact++)
    for (int per = 0; per < 8; per++) {
      const mpm_mesh m = sep_mesh(dims[(per + exact) % 3], per, exact);
      for (int ppu = 1; ppu <= 3; ppu++) {
        mpm_points *P = mpm_points_alloc_dim(0, 3);
        ck_assert_ptr_nonnull(P);
        for (int t = 0; t < 400; t++) {
          size_t i;
          ck_assert_int_eq(mpm_points_push(P, &i), MPM_OK);
          const int kind = t % 5;
          for (int d = 0; d < 3; d++) {
            const double hw = 0.5 * m.h[d] / ppu;
            const int k = kind == 1 && d != t / 5 % 3 ? 0 : kind;   /* one axis near a face */
            const double x = sep_coord(&m, d, k, hw, ppu, &s);
            P->pos[d][i] = x;
            P->ext[d][d][i] = uni(&s) < 0.5 ? -hw : hw;
            const int below = x - hw < m.o[d], above = x + hw > m.o[d] + m.len[d];
            clamped += !m.periodic[d] && (below || above);
            seam += m.periodic[d] && x >= m.o[d] && x < m.o[d] + m.len[d] &&
                    (below || x + hw >= m.o[d] + m.len[d]);
          }
        }
        mpm_shape_stencil *st = mpm_shape_stencil_alloc(0);
        ck_assert_ptr_nonnull(st);
        mpm_err err = {0};
        ck_assert_msg(mpm_shape_stencil_compute(st, &mpm_shape_ugimp, &m, P, 0.0, &err) ==
                      MPM_OK, "%s", err.msg);
        ck_assert_int_eq(st->sep, 1);             /* the factorised form was taken */
        ck_assert_int_eq(st->dim, 3);
        for (size_t p = 0; p < P->n; p++)
          sep_compare(&m, P, st, p);
        total += (long)P->n;
        mpm_shape_stencil_free(st);
        mpm_points_free(P);
      }
    }
  printf("factorised stencil: %ld points, %ld axes with clamped corners, %ld across a seam\n",
         total, clamped, seam);
  ck_assert_int_gt(clamped, 1000);
  ck_assert_int_gt(seam, 1000);
}
END_TEST

/* Per storage node, folded: sums of S and dS over the nodes of the list
 * whose logical index along the folded axes is congruent mod f[d] (f = 1:
 * no folding), into sums[((k f2 + ...)...]: a flat array indexed by the
 * folded (i, j, k) in [0, f0) x [0, sny) x [0, f2). */
static void fold(const mpm_mesh *m, int cnt, const int *node, const double *S,
                 double *const dS[3], const int f[3], double (*sums)[4])
{
  for (int k = 0; k < cnt; k++) {
    const int ijk[3] = {node[k] % m->snx, node[k] / m->snx % m->sny,
                        node[k] / (m->snx * m->sny)};
    const int i = ijk[0] % f[0], j = ijk[1] % f[1], z = ijk[2] % f[2];
    double *a = sums[(z * f[1] + j) * f[0] + i];
    a[0] += S[k];
    for (int d = 0; d < m->dim; d++)
      a[1 + d] += dS[d][k];
  }
}

/* Periodic axes of one and two units, where nodes that a point reaches from
 * both sides are one stored node (merged): the weights still sum to 1 and
 * their gradients to 0, the nodes of a list are distinct, and the weights
 * are those of a mesh of four units along the same axes (the same field
 * repeated) summed over the nodes that alias, for extents of fills of 1, 2
 * and 3 points a unit and wider ones (up to 0.9 units: a corner pair over
 * two units of a two-unit axis). On boxes: x and z of two units through the
 * stencil of a store; in the plane, where a periodic axis of one unit is
 * allowed (a box refuses it: it would be its own neighbour), the
 * factorised rule itself (mpm_shape_in_separable, written for both
 * dimensions) on axes of one and two units. Round-off as in sep_compare,
 * summed over at most 4 aliased nodes: 1e-14 (gradients times the
 * half-width). */
START_TEST(t_separable_short_periodic)
{
  uint64_t s = 0x2A1A5ULL;
  /* boxes: x, z periodic on 2 units against 4 */
  for (int ppu = 0; ppu <= 3; ppu++) {
    const int n2[3] = {2, 5, 2}, n4[3] = {4, 5, 4};
    const mpm_mesh a = sep_mesh(n2, 5, ppu % 2), b = sep_mesh(n4, 5, ppu % 2);
    mpm_points *P = mpm_points_alloc_dim(0, 3);
    for (int t = 0; t < 300; t++) {
      size_t i;
      ck_assert_int_eq(mpm_points_push(P, &i), MPM_OK);
      for (int d = 0; d < 3; d++) {
        const double hw = (ppu ? 0.5 / ppu : 0.05 + 0.85 * uni(&s)) * a.h[d];
        P->pos[d][i] = a.o[d] + a.len[d] * uni(&s);
        if (t % 7 == 0 && d != 1)
          P->pos[d][i] = a.o[d] + (int)(3.0 * uni(&s)) * a.h[d];   /* on a node, seam included */
        P->ext[d][d][i] = uni(&s) < 0.5 ? -hw : hw;
      }
    }
    mpm_shape_stencil *sa = mpm_shape_stencil_alloc(0), *sb = mpm_shape_stencil_alloc(0);
    mpm_err err = {0};
    ck_assert_int_eq(mpm_shape_stencil_compute(sa, &mpm_shape_ugimp, &a, P, 0.0, &err), MPM_OK);
    ck_assert_int_eq(mpm_shape_stencil_compute(sb, &mpm_shape_ugimp, &b, P, 0.0, &err), MPM_OK);
    ck_assert_int_eq(sa->sep, 1);
    ck_assert_int_eq(sb->sep, 1);
    for (size_t p = 0; p < P->n; p++) {
      double hw[3];
      for (int d = 0; d < 3; d++)
        hw[d] = fabs(P->ext[d][d][p]);
      int na[W], nb[W];
      double Sa[W], Sb[W], ga[3][W], gb[3][W];
      double *const da[3] = {ga[0], ga[1], ga[2]}, *const db[3] = {gb[0], gb[1], gb[2]};
      const int ca = mpm_shape_stencil_list(sa, &a, p, na, Sa, da);
      const int cb = mpm_shape_stencil_list(sb, &b, p, nb, Sb, db);
      double s0 = 0.0, g0[3] = {0.0, 0.0, 0.0};
      for (int k = 0; k < ca; k++) {
        for (int q = 0; q < k; q++)
          ck_assert_int_ne(na[k], na[q]);          /* merged: each node once */
        s0 += Sa[k];
        for (int d = 0; d < 3; d++)
          g0[d] += ga[d][k];
      }
      ck_assert_double_eq_tol(s0, 1.0, 1e-14);
      for (int d = 0; d < 3; d++)
        ck_assert_double_le(fabs(g0[d]) * hw[d], 1e-14);
      const int f[3] = {2, a.sny, 2};
      double fa[2 * 6 * 2][4], fb[2 * 6 * 2][4];
      memset(fa, 0, sizeof fa);
      memset(fb, 0, sizeof fb);
      fold(&a, ca, na, Sa, da, f, fa);
      fold(&b, cb, nb, Sb, db, f, fb);
      for (int q = 0; q < 2 * 6 * 2; q++) {
        ck_assert_double_eq_tol(fa[q][0], fb[q][0], 1e-14);
        for (int d = 0; d < 3; d++)
          ck_assert_double_le(fabs(fa[q][1 + d] - fb[q][1 + d]) * hw[d], 1e-14);
      }
    }
    mpm_shape_stencil_free(sa);
    mpm_shape_stencil_free(sb);
    mpm_points_free(P);
  }
  /* the plane: x periodic on 1 and 2 units against 4, y of 6 units */
  for (int nx = 1; nx <= 2; nx++)
    for (int t = 0; t < 600; t++) {
      mpm_mesh m[2];
      for (int q = 0; q < 2; q++) {
        memset(&m[q], 0, sizeof m[q]);
        m[q].nx = q ? 4 : nx;
        m[q].ny = 6;
        m[q].x0 = -0.4;
        m[q].y0 = 0.25;
        m[q].dx = 0.13;
        m[q].dy = 0.11;
        m[q].periodic_x = 1;
        mpm_err err = {0};
        ck_assert_int_eq(mpm_mesh_setup(&m[q], &err), MPM_OK);
      }
      const int ppu = t % 4;
      const double h[3] = {(ppu ? 0.5 / ppu : 0.05 + 0.85 * uni(&s)) * m[0].dx,
                           (ppu ? 0.5 / ppu : 0.05 + 0.85 * uni(&s)) * m[0].dy, 0.0};
      const double x[3] = {m[0].x0 + m[0].lx * uni(&s), m[0].y0 + m[0].ly * uni(&s), 0.0};
      double sums[2][6 * 7][4];
      memset(sums, 0, sizeof sums);
      for (int q = 0; q < 2; q++) {
        int c[3];
        double l[3];
        ck_assert_int_eq(mpm_mesh_locate(&m[q], x, c, l), 0);
        mpm_shape_axes ax;
        ck_assert_int_eq(mpm_shape_in_separable(&m[q], x, c, h, &ax), 0);
        int node[W];
        double S[W], gx[W], gy[W];
        double *const dS[3] = {gx, gy, NULL};
        const int cnt = mpm_shape_in_separable_list(&m[q], &ax, node, S, dS);
        if (q == 0) {
          double s0 = 0.0, g0[2] = {0.0, 0.0};
          for (int k = 0; k < cnt; k++) {
            for (int u = 0; u < k; u++)
              ck_assert_int_ne(node[k], node[u]);
            s0 += S[k];
            g0[0] += gx[k];
            g0[1] += gy[k];
          }
          ck_assert_double_eq_tol(s0, 1.0, 1e-14);
          ck_assert_double_le(fabs(g0[0]) * h[0], 1e-14);
          ck_assert_double_le(fabs(g0[1]) * h[1], 1e-14);
        }
        const int f[3] = {nx, m[q].sny, 1};
        fold(&m[q], cnt, node, S, dS, f, sums[q]);
      }
      for (int q = 0; q < nx * 7; q++) {
        ck_assert_double_eq_tol(sums[0][q][0], sums[1][q][0], 1e-14);
        for (int d = 0; d < 2; d++)
          ck_assert_double_le(fabs(sums[0][q][1 + d] - sums[1][q][1 + d]) * h[d], 1e-14);
      }
    }
}
END_TEST

int main(void)
{
  Suite *s = suite_create("box_shape");
  TCase *tc = tcase_create("box_shape");
  tcase_set_timeout(tc, 120);
  tcase_add_test(tc, t_box_corner_rule);
  tcase_add_test(tc, t_box_invariants_delta);
  tcase_add_test(tc, t_box_invariants_ugimp);
  tcase_add_test(tc, t_box_invariants_ugimp_wide);
  tcase_add_test(tc, t_box_invariants_cpdi);
  tcase_add_test(tc, t_box_ugimp_box_is_delta);
  tcase_add_test(tc, t_box_ugimp_rotated_hand);
  tcase_add_test(tc, t_box_ugimp_on_node);
  tcase_add_test(tc, t_box_ugimp_clamped);
  tcase_add_test(tc, t_box_ugimp_periodic);
  tcase_add_test(tc, t_box_ugimp_box_factorised);
  tcase_add_test(tc, t_box_ugimp_nonfinite);
  tcase_add_test(tc, t_box_convect);
  tcase_add_test(tc, t_box_registry);
  tcase_add_test(tc, t_separable_batch_is_per_point);
  tcase_add_test(tc, t_separable_fill_nodes);
  tcase_add_test(tc, t_separable_short_periodic);
  suite_add_tcase(s, tc);
  SRunner *sr = srunner_create(s);
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf ? EXIT_FAILURE : EXIT_SUCCESS;
}
