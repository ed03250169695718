/* test_shape.c: unit tests of the shape variants and the stencil
 * (MODEL.md section 3).
 *
 * The core checks are the V0 kernel invariants of the verification plan
 * (VERIFICATION.md, case V0; MODEL.md section 3): for every variant, on Q4 and
 * T3 with each diagonal rule, periodic or not, at random points with random
 * (rotated, sheared, either orientation) extents,
 *   sum_i S_ip = 1,  sum_i gradS_ip = 0,  sum_i S_ip x_i = x_p,
 *   sum_i x_i (x) gradS_ip = I.
 * Near a periodic edge the stencil holds storage ids; each is mapped back to
 * the logical node nearest the point (its stored position shifted by whole
 * periods), which is the node the point actually touches as long as the
 * stencil spans less than half the period (true for the meshes below).
 *
 * Tolerances: positions are O(1) m, weights O(1), gradients O(1/dx) ~ 10 /m,
 * sums have at most 16 terms: round-off is below 16 * 10 * 1 * 2.2e-16 ~ 4e-14,
 * so 1e-12 is safe, while any wrong weight or sign errs by O(0.01) or more.
 * Hand-computed values (nodes, clamping) are checked to the same 1e-12. */
#include <check.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/points.h"
#include "mesh/mesh.h"
#include "shape/shape.h"
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

static mpm_mesh make_mesh(int nx, int ny, int topo, int diag, int px, int py)
{
  mpm_mesh m;
  memset(&m, 0, sizeof m);
  m.nx = nx;
  m.ny = ny;
  m.x0 = -0.4;
  m.y0 = 0.25;
  m.dx = 0.13;
  m.dy = 0.11;
  m.topology = topo;
  m.diagonal = diag;
  m.mirror_x = m.x0 + 3 * m.dx;
  m.periodic_x = px;
  m.periodic_y = py;
  mpm_err err = {0};
  ck_assert_int_eq(mpm_mesh_setup(&m, &err), MPM_OK);
  return m;
}

/* Stored position of node id shifted by whole periods to lie nearest (xp, yp). */
static void node_near(const mpm_mesh *m, int id, double xp, double yp,
                      double *x, double *y)
{
  plane_node_pos(m, id % m->snx, id / m->snx, x, y);
  if (m->periodic_x)
    *x += m->lx * round((xp - *x) / m->lx);
  if (m->periodic_y)
    *y += m->ly * round((yp - *y) / m->ly);
}

/* Random extent: |r1|, |r2| in [lo, hi] * min(dx, dy), any rotation, angle
 * between them at least ~17 degrees away from parallel, either orientation. */
static void random_extent(const mpm_mesh *m, uint64_t *s, double lo, double hi,
                          double r[4])
{
  const double h = fmin(m->dx, m->dy), pi = acos(-1.0);
  const double a1 = h * (lo + (hi - lo) * rnd(s)), a2 = h * (lo + (hi - lo) * rnd(s));
  const double t1 = 2 * pi * rnd(s);
  double t2 = t1 + (0.1 + 0.8 * rnd(s)) * pi;  /* sin(t2 - t1) >= sin(0.1 pi) */
  if (rnd(s) < 0.5)
    t2 = t1 - (t2 - t1);                         /* clockwise: A_p < 0 */
  r[0] = a1 * cos(t1);
  r[1] = a1 * sin(t1);
  r[2] = a2 * cos(t2);
  r[3] = a2 * sin(t2);
}

/* Random point: on a periodic axis anywhere in [o - h, o + len + h]; otherwise
 * far enough from the edges that no corner is clamped (margin). */
static double random_coord(uint64_t *s, double o, double len, double h,
                           int periodic, double margin)
{
  if (periodic)
    return o - h + (len + 2 * h) * rnd(s);
  return o + margin + (len - 2 * margin) * rnd(s);
}

/* Evaluate type at (xp, yp, r), check ids (valid, distinct) and the four
 * invariants; returns the node count. */
static int check_invariants(const mpm_mesh *m, const mpm_shape_type *type,
                            double xp, double yp, const double r[4])
{
  int node[MPM_STENCIL_W];
  double S[MPM_STENCIL_W], gx[MPM_STENCIL_W], gy[MPM_STENCIL_W];
  const int n = plane_eval(type, m, xp, yp, r, node, S, gx, gy);
  ck_assert_int_ge(n, 3);
  ck_assert_int_le(n, MPM_STENCIL_W);
  double s0 = 0, gsx = 0, gsy = 0, mx = 0, my = 0;
  double Ixx = 0, Ixy = 0, Iyx = 0, Iyy = 0;
  for (int k = 0; k < n; k++) {
    ck_assert_int_ge(node[k], 0);
    ck_assert_int_lt(node[k], m->nnodes);
    for (int l = 0; l < k; l++)
      ck_assert_int_ne(node[k], node[l]);  /* merged: each node once */
    double xi, yi;
    node_near(m, node[k], xp, yp, &xi, &yi);
    s0 += S[k];                            /* sum S */
    gsx += gx[k];                          /* sum gradS */
    gsy += gy[k];
    mx += S[k] * xi;                       /* sum S x_i */
    my += S[k] * yi;
    Ixx += xi * gx[k];                     /* sum x_i (x) gradS */
    Ixy += xi * gy[k];
    Iyx += yi * gx[k];
    Iyy += yi * gy[k];
  }
  ck_assert_double_eq_tol(s0, 1.0, TOL);
  ck_assert_double_eq_tol(gsx, 0.0, TOL);
  ck_assert_double_eq_tol(gsy, 0.0, TOL);
  /* the mesh may wrap xp: compare with the logical position nearest xp */
  ck_assert_double_eq_tol(mx, xp, TOL);
  ck_assert_double_eq_tol(my, yp, TOL);
  ck_assert_double_eq_tol(Ixx, 1.0, TOL);
  ck_assert_double_eq_tol(Ixy, 0.0, TOL);
  ck_assert_double_eq_tol(Iyx, 0.0, TOL);
  ck_assert_double_eq_tol(Iyy, 1.0, TOL);
  return n;
}

static const int topo_of[4] = {MPM_TOPO_Q4, MPM_TOPO_T3, MPM_TOPO_T3, MPM_TOPO_T3};
static const int diag_of[4] = {MPM_DIAG_SLASH, MPM_DIAG_SLASH, MPM_DIAG_BACKSLASH,
                               MPM_DIAG_MIRROR};

/* V0 invariants: mesh kind k (Q4, T3 /, T3 \, T3 mirror) x periodicity. */
static void invariants_on(const mpm_shape_type *type, double rlo, double rhi,
                          int nx, int ny, uint64_t seed)
{
  uint64_t s = seed;
  for (int k = 0; k < 4; k++)
    for (int per = 0; per < 4; per++) {
      mpm_mesh m = make_mesh(nx, ny, topo_of[k], diag_of[k], per & 1, per >> 1);
      for (int trial = 0; trial < 500; trial++) {
        double r[4];
        random_extent(&m, &s, rlo, rhi, r);
        const double mx = fabs(r[0]) + fabs(r[2]), my = fabs(r[1]) + fabs(r[3]);
        const double xp = random_coord(&s, m.x0, m.lx, m.dx, m.periodic_x, mx);
        const double yp = random_coord(&s, m.y0, m.ly, m.dy, m.periodic_y, my);
        check_invariants(&m, type, xp, yp, r);
      }
    }
}

START_TEST(t_invariants_delta)
{
  invariants_on(&mpm_shape_delta, 0.1, 0.5, 7, 6, 0x1234567ULL);
}
END_TEST

START_TEST(t_invariants_ugimp)
{
  invariants_on(&mpm_shape_ugimp, 0.1, 0.5, 7, 6, 0xC0FFEEULL);
}
END_TEST

/* Extents larger than a unit put corners in non-adjacent units: up to 16
 * distinct nodes, and the corner rule stays exact for linear fields. */
START_TEST(t_invariants_ugimp_wide)
{
  invariants_on(&mpm_shape_ugimp, 0.5, 1.5, 14, 14, 0xBADF00DULL);
  mpm_mesh m = make_mesh(14, 14, MPM_TOPO_Q4, MPM_DIAG_SLASH, 0, 0);
  const double r[4] = {1.2 * m.dx, 0.0, 0.0, 1.2 * m.dy};
  const int n = check_invariants(&m, &mpm_shape_ugimp, m.x0 + 7.5 * m.dx,
                                 m.y0 + 7.5 * m.dy, r);
  ck_assert_int_eq(n, 16);  /* 4 separate units, 4 nodes each */
}
END_TEST

/* Evaluate the extent r at (xp, yp) on the faster path (r1y = r2x = 0) and
 * on the general rule, reached with r1y = 1e-300: every sum the rule forms
 * then rounds to the one with r1y = 0 (1e-300 is far below half an ulp of
 * the other terms), so the two must agree bit for bit on every node both
 * list. Both lists run in row order (the fast path has no periodic seam
 * inside its units); a node only one of them lists must weigh exactly 0
 * there. Returns how many nodes only the fast path lists. */
static int axes_against_general(const mpm_mesh *m, double xp, double yp, double a, double b)
{
  const double ra[4] = {a, 0.0, 0.0, b}, rg[4] = {a, 1e-300, 0.0, b};
  int na[MPM_STENCIL_W], ng[MPM_STENCIL_W];
  double Sa[MPM_STENCIL_W], xa[MPM_STENCIL_W], ya[MPM_STENCIL_W];
  double Sg[MPM_STENCIL_W], xg[MPM_STENCIL_W], yg[MPM_STENCIL_W];
  const int ca = plane_eval(&mpm_shape_ugimp, m, xp, yp, ra, na, Sa, xa, ya);
  const int cg = plane_eval(&mpm_shape_ugimp, m, xp, yp, rg, ng, Sg, xg, yg);
  ck_assert_int_gt(ca, 0);
  ck_assert_int_gt(cg, 0);
  int q = 0, l = 0, extra = 0;
  while (q < ca || l < cg) {
    if (q < ca && l < cg && na[q] == ng[l]) {
      ck_assert(memcmp(&Sa[q], &Sg[l], sizeof(double)) == 0);
      ck_assert(memcmp(&xa[q], &xg[l], sizeof(double)) == 0);
      ck_assert(memcmp(&ya[q], &yg[l], sizeof(double)) == 0);
      q++;
      l++;
    } else if (q < ca && (l == cg || na[q] < ng[l])) {
      ck_assert(Sa[q] == 0.0 && xa[q] == 0.0 && ya[q] == 0.0);
      q++;
      extra++;
    } else {
      ck_assert(Sg[l] == 0.0 && xg[l] == 0.0 && yg[l] == 0.0);
      l++;
    }
  }
  return extra;
}

/* An extent along the axes, r = (r1x, 0, 0, r2y) (every uGIMP point as
 * filled), is evaluated by a faster path that must give the general rule's
 * weights bit for bit (axes_against_general); the two lists may differ in
 * nodes of weights 0 only (a node of the units the corners fall in that no
 * corner's element holds, or one the rule gives exactly 0). Extents of 0.05
 * to 1.6 units of either sign, points anywhere (corners clamped or wrapped
 * included), all mesh kinds and periodicities, and a periodic mesh of two
 * units (merged nodes); the invariants hold too where no corner is
 * clamped. Then points as a fill places them (2 x 2 and 4 x 4 a unit,
 * quarter- and eighth-unit extents) on a mesh whose units are exact binary
 * fractions: their corners lie exactly on unit edges, where weights are
 * exactly 0. */
START_TEST(t_ugimp_axes_bitwise)
{
  uint64_t s = 0xA11A5ULL;
  int extra = 0;
  for (int k = 0; k < 4; k++)
    for (int per = 0; per < 8; per++) {
      const int few = per >= 4;
      mpm_mesh m = make_mesh(few ? 2 : 7, few ? 3 : 6, topo_of[k], diag_of[k], per & 1,
                             per >> 1 & 1);
      for (int trial = 0; trial < 400; trial++) {
        const double a = (0.05 + 1.55 * rnd(&s)) * m.dx * (rnd(&s) < 0.5 ? -1.0 : 1.0);
        const double b = (0.05 + 1.55 * rnd(&s)) * m.dy * (rnd(&s) < 0.5 ? -1.0 : 1.0);
        const double xp = random_coord(&s, m.x0, m.lx, m.dx, m.periodic_x, 0.0);
        const double yp = random_coord(&s, m.y0, m.ly, m.dy, m.periodic_y, 0.0);
        extra += axes_against_general(&m, xp, yp, a, b);
        const double ra[4] = {a, 0.0, 0.0, b};
        const int cx = xp - fabs(a) < m.x0 || xp + fabs(a) > m.x0 + m.lx;
        const int cy = yp - fabs(b) < m.y0 || yp + fabs(b) > m.y0 + m.ly;
        const int clamped = (!m.periodic_x && cx) || (!m.periodic_y && cy);
        if (!few && !clamped)                /* the invariants hold away from clamped edges */
          check_invariants(&m, &mpm_shape_ugimp, xp, yp, ra);
      }
    }
  ck_assert_int_gt(extra, 0);                /* the fast path was taken */
  for (int k = 0; k < 4; k++) {
    mpm_mesh m = make_mesh(6, 5, topo_of[k], diag_of[k], 0, 0);
    m.x0 = 0.0;
    m.y0 = 0.0;
    m.dx = 0.125;
    m.dy = 0.25;
    m.mirror_x = 3 * m.dx;
    mpm_err err = {0};
    ck_assert_int_eq(mpm_mesh_setup(&m, &err), MPM_OK);
    for (int ppu = 2; ppu <= 4; ppu += 2)
      for (int j = 0; j < m.ny * ppu; j++)
        for (int i = 0; i < m.nx * ppu; i++)
          axes_against_general(&m, (i + 0.5) * m.dx / ppu, (j + 0.5) * m.dy / ppu,
                               0.5 * m.dx / ppu, 0.5 * m.dy / ppu);
  }
}
END_TEST

/* CPDI1 extents are parallelograms the deformation made: sheared,
 * stretched to 1.5 units or squeezed to 0.1, either orientation. */
START_TEST(t_invariants_cpdi)
{
  invariants_on(&mpm_shape_cpdi, 0.1, 1.5, 14, 14, 0xFEEDULL);
}
END_TEST

/* The convection of an extent, r_k <- (I + dt L) r_k, step by step.
 * A rigid spin L = [[0, -w], [w, 0]]: I + dt L is sqrt(1 + (w dt)^2) times
 * the rotation by atan(w dt), so after n steps r_k has turned by
 * n atan(w dt) and grown by (1 + (w dt)^2)^(n/2), exactly (round-off
 * 1e-13 over 1000 steps). A uniaxial stretch rate L = diag(e, 0) leaves r
 * along y alone and scales x by (1 + e dt)^n. */
START_TEST(t_cpdi_convect)
{
  const double w = 3.0, dt = 1e-3, e = -2.0;
  const int n = 1000;
  double a[4] = {0.4, 0.1, -0.05, 0.3}, b[4] = {0.4, 0.1, -0.05, 0.3};
  const double spin[4] = {0.0, -w, w, 0.0}, stretch[4] = {e, 0.0, 0.0, 0.0};
  for (int k = 0; k < n; k++) {
    mpm_shape_extent_convect_dim(2, a, spin, dt);
    mpm_shape_extent_convect_dim(2, b, stretch, dt);
  }
  const double th = n * atan(w * dt), g = pow(1.0 + w * dt * w * dt, 0.5 * n);
  const double c = cos(th), sn = sin(th), sx = pow(1.0 + e * dt, n);
  const double r0[4] = {0.4, 0.1, -0.05, 0.3};
  for (int k = 0; k < 2; k++) {
    const double x = r0[2 * k], y = r0[2 * k + 1];
    ck_assert_double_eq_tol(a[2 * k], g * (c * x - sn * y), 1e-13);
    ck_assert_double_eq_tol(a[2 * k + 1], g * (sn * x + c * y), 1e-13);
    ck_assert_double_eq_tol(b[2 * k], sx * x, 1e-13);
    ck_assert_double_eq(b[2 * k + 1], y);
  }
}
END_TEST

/* Inside one element, where N is linear (T3) or bilinear with an axis-aligned
 * extent (Q4), the corner averages equal the values at the centre: uGIMP
 * weights must equal the delta weights there. */
static void expect_same_as_delta(const mpm_mesh *m, double xp, double yp,
                                 const double r[4])
{
  int na[MPM_STENCIL_W], nb[MPM_STENCIL_W];
  double Sa[MPM_STENCIL_W], xa[MPM_STENCIL_W], ya[MPM_STENCIL_W];
  double Sb[MPM_STENCIL_W], xb[MPM_STENCIL_W], yb[MPM_STENCIL_W];
  const int a = plane_eval(&mpm_shape_delta, m, xp, yp, r, na, Sa, xa, ya);
  const int b = plane_eval(&mpm_shape_ugimp, m, xp, yp, r, nb, Sb, xb, yb);
  ck_assert_int_eq(a, b);
  for (int k = 0; k < a; k++) {
    int l = 0;
    while (l < b && nb[l] != na[k])
      l++;
    ck_assert_int_lt(l, b);
    ck_assert_double_eq_tol(Sb[l], Sa[k], TOL);
    ck_assert_double_eq_tol(xb[l], xa[k], TOL);
    ck_assert_double_eq_tol(yb[l], ya[k], TOL);
  }
}

START_TEST(t_ugimp_inside_one_element)
{
  mpm_mesh q = make_mesh(7, 6, MPM_TOPO_Q4, MPM_DIAG_SLASH, 0, 0);
  const double rq[4] = {0.2 * q.dx, 0.0, 0.0, -0.15 * q.dy};  /* clockwise */
  expect_same_as_delta(&q, q.x0 + 2.4 * q.dx, q.y0 + 3.55 * q.dy, rq);
  /* "/" unit, lower-right triangle around (u, v) = (0.7, 0.25), rotated */
  mpm_mesh t = make_mesh(7, 6, MPM_TOPO_T3, MPM_DIAG_SLASH, 0, 0);
  const double c = cos(0.6), sn = sin(0.6);
  const double rt[4] = {0.08 * t.dx * c, 0.08 * t.dy * sn, -0.06 * t.dx * sn,
                        0.06 * t.dy * c};
  expect_same_as_delta(&t, t.x0 + 4.7 * t.dx, t.y0 + 1.25 * t.dy, rt);
}
END_TEST

/* Point on node (3, 2) with r1 = (h, 0), r2 = (0, h), h < dx, dy: by hand
 * each corner sees N_(3,2) = (1 - h/dx)(1 - h/dy), so S = that; node (4, 3)
 * is seen by x3 only: S = (h/dx)(h/dy)/4; node (4, 2) by x2 and x3 with
 * N = (h/dx)(1 - h/dy): S = N/2, gradS = (N/(2h), 0). */
START_TEST(t_ugimp_hand_values)
{
  mpm_mesh m = make_mesh(7, 6, MPM_TOPO_Q4, MPM_DIAG_SLASH, 0, 0);
  const double h = 0.03;
  const double r[4] = {h, 0.0, 0.0, h};
  double xp, yp;
  plane_node_pos(&m, 3, 2, &xp, &yp);
  int node[MPM_STENCIL_W];
  double S[MPM_STENCIL_W], gx[MPM_STENCIL_W], gy[MPM_STENCIL_W];
  const int n = plane_eval(&mpm_shape_ugimp, &m, xp, yp, r, node, S, gx, gy);
  ck_assert_int_eq(n, 9);
  const double ux = h / m.dx, uy = h / m.dy;
  int seen = 0;
  for (int k = 0; k < n; k++) {
    if (node[k] == plane_node(&m, 3, 2)) {
      ck_assert_double_eq_tol(S[k], (1 - ux) * (1 - uy), TOL);
      ck_assert_double_eq_tol(gx[k], 0.0, TOL);
      ck_assert_double_eq_tol(gy[k], 0.0, TOL);
      seen++;
    } else if (node[k] == plane_node(&m, 4, 3)) {
      ck_assert_double_eq_tol(S[k], ux * uy / 4, TOL);
      seen++;
    } else if (node[k] == plane_node(&m, 4, 2)) {
      const double N = ux * (1 - uy);
      ck_assert_double_eq_tol(S[k], N / 2, TOL);
      ck_assert_double_eq_tol(gx[k], N / (2 * h), TOL);
      ck_assert_double_eq_tol(gy[k], 0.0, TOL);
      seen++;
    }
  }
  ck_assert_int_eq(seen, 3);
}
END_TEST

/* Corners beyond a non-periodic edge are clamped onto it. Point at
 * (x0 + 0.1 dx, y0 + 2.5 dy), r1 = (0.4 dx, 0), r2 = (0, 0.25 dy): the x
 * corners go to x0 (clamped from x0 - 0.3 dx) and x0 + 0.5 dx, so along x
 * node column 0 gets (1 + 0.5)/2 = 0.75 and column 1 gets 0.25; along y the
 * rows 2 and 3 get 1/2 each. */
START_TEST(t_ugimp_clamped)
{
  mpm_mesh m = make_mesh(7, 6, MPM_TOPO_Q4, MPM_DIAG_SLASH, 0, 0);
  const double r[4] = {0.4 * m.dx, 0.0, 0.0, 0.25 * m.dy};
  int node[MPM_STENCIL_W];
  double S[MPM_STENCIL_W], gx[MPM_STENCIL_W], gy[MPM_STENCIL_W];
  const int n = plane_eval(&mpm_shape_ugimp, &m, m.x0 + 0.1 * m.dx, m.y0 + 2.5 * m.dy, r,
                                     node, S, gx, gy);
  ck_assert_int_eq(n, 4);
  double s0 = 0, gsx = 0, gsy = 0;
  for (int k = 0; k < n; k++) {
    const int i = node[k] % m.snx;
    ck_assert_double_eq_tol(S[k], (i == 0 ? 0.75 : 0.25) * 0.5, TOL);
    s0 += S[k];
    gsx += gx[k];
    gsy += gy[k];
  }
  ck_assert_double_eq_tol(s0, 1.0, TOL);   /* partition of unity survives */
  ck_assert_double_eq_tol(gsx, 0.0, TOL);
  ck_assert_double_eq_tol(gsy, 0.0, TOL);
  /* centres on the edges and corners: inside; just beyond: outside */
  const double big[4] = {0.45 * m.dx, 0.1 * m.dy, -0.1 * m.dx, 0.45 * m.dy};
  ck_assert_int_gt(plane_eval(&mpm_shape_ugimp, &m, m.x0, m.y0, big, node, S, gx, gy), 0);
  ck_assert_int_gt(plane_eval(&mpm_shape_ugimp, &m, m.x0 + m.lx, m.y0 + m.ly, big, node, S,
                                        gx, gy), 0);
  ck_assert_int_eq(plane_eval(&mpm_shape_ugimp, &m, m.x0 - 1e-9, m.y0 + 0.1, big, node, S,
                                        gx, gy), -1);
  ck_assert_int_eq(plane_eval(&mpm_shape_delta, &m, m.x0 - 1e-9, m.y0 + 0.1, big, node, S,
                                        gx, gy), -1);
  ck_assert_int_eq(plane_eval(&mpm_shape_ugimp, &m, m.x0 + 0.1, m.y0 + m.ly + 1e-9, big,
                                        node, S, gx, gy), -1);
}
END_TEST

/* Along a periodic x the same point is not clamped: corners wrap to the last
 * node column, which is stored as column nx - 1. */
START_TEST(t_ugimp_periodic_wrap)
{
  mpm_mesh m = make_mesh(7, 6, MPM_TOPO_Q4, MPM_DIAG_SLASH, 1, 0);
  const double r[4] = {0.4 * m.dx, 0.0, 0.0, 0.25 * m.dy};
  int node[MPM_STENCIL_W];
  double S[MPM_STENCIL_W], gx[MPM_STENCIL_W], gy[MPM_STENCIL_W];
  const int n = plane_eval(&mpm_shape_ugimp, &m, m.x0 + 0.1 * m.dx, m.y0 + 2.5 * m.dy, r,
                                     node, S, gx, gy);
  ck_assert_int_eq(n, 6);  /* columns nx-1, 0, 1 times rows 2, 3 */
  int last = 0;
  for (int k = 0; k < n; k++)
    if (node[k] % m.snx == m.nx - 1) {
      /* left corners at x0 - 0.3 dx: N of column nx - 1 is 0.3, half the corners */
      ck_assert_double_eq_tol(S[k], 0.5 * 0.3 * 0.5, TOL);
      last++;
    }
  ck_assert_int_eq(last, 2);
  /* the same point given one period to the right has the same stencil */
  int node2[MPM_STENCIL_W];
  double S2[MPM_STENCIL_W], gx2[MPM_STENCIL_W], gy2[MPM_STENCIL_W];
  ck_assert_int_eq(plane_eval(&mpm_shape_ugimp, &m, m.x0 + m.lx + 0.1 * m.dx,
                                        m.y0 + 2.5 * m.dy, r, node2, S2, gx2, gy2),
                   n);
  for (int k = 0; k < n; k++) {
    ck_assert_int_eq(node2[k], node[k]);
    ck_assert_double_eq_tol(S2[k], S[k], TOL);
    ck_assert_double_eq_tol(gx2[k], gx[k], TOL);
    ck_assert_double_eq_tol(gy2[k], gy[k], TOL);
  }
}
END_TEST

/* A periodic x axis of one unit ([DK15] section 4.4 on one column of
 * elements): its two node columns are one node, so a nodal field can only
 * vary along y, and a point must weigh it exactly as it weighs that field
 * (the same value on every node of a row) on a wider periodic mesh. Per
 * node row, the sums of S, dS/dx and dS/dy over the listed nodes (a node
 * may be listed twice) equal those on 3 units, for every shape and
 * topology, at random points and extents up to half a unit. */
static void row_sums(const mpm_mesh *m, const mpm_shape_type *type, double xp, double yp,
                     const double r[4], double sums[][3], int nrow)
{
  int node[MPM_STENCIL_W];
  double S[MPM_STENCIL_W], gx[MPM_STENCIL_W], gy[MPM_STENCIL_W];
  const int n = plane_eval(type, m, xp, yp, r, node, S, gx, gy);
  ck_assert_int_ge(n, 1);
  for (int j = 0; j < nrow; j++)
    sums[j][0] = sums[j][1] = sums[j][2] = 0.0;
  for (int k = 0; k < n; k++) {
    const int j = node[k] / m->snx;
    ck_assert_int_lt(j, nrow);
    sums[j][0] += S[k];
    sums[j][1] += gx[k];
    sums[j][2] += gy[k];
  }
}

START_TEST(t_one_unit_periodic)
{
  const mpm_shape_type *types[] = {&mpm_shape_delta, &mpm_shape_ugimp, &mpm_shape_cpdi};
  const int topo[3][2] = {{MPM_TOPO_Q4, MPM_DIAG_SLASH},
                          {MPM_TOPO_T3, MPM_DIAG_SLASH},
                          {MPM_TOPO_T3, MPM_DIAG_BACKSLASH}};
  uint64_t seed = 20261127;
  for (int t = 0; t < 3; t++)
    for (int q = 0; q < 3; q++) {
      const mpm_mesh one = make_mesh(1, 6, topo[q][0], topo[q][1], 1, 0);
      const mpm_mesh three = make_mesh(3, 6, topo[q][0], topo[q][1], 1, 0);
      ck_assert_int_eq(one.snx, 1);
      for (int trial = 0; trial < 200; trial++) {
        double r[4] = {0.0, 0.0, 0.0, 0.0};
        if (types[t] != &mpm_shape_delta)
          random_extent(&one, &seed, 0.05, 0.5, r);
        if (trial % 2 && types[t] != &mpm_shape_delta) {   /* along the axes, as filled */
          r[0] = (0.05 + 0.45 * rnd(&seed)) * one.dx;
          r[3] = (0.05 + 0.45 * rnd(&seed)) * one.dy;
          r[1] = r[2] = 0.0;
        }
        const double xp = random_coord(&seed, one.x0, one.lx, one.dx, 1, 0.0);
        const double yp = random_coord(&seed, one.y0, one.ly, one.dy, 0, 0.8 * one.dy);
        double a[7][3], b[7][3];
        row_sums(&one, types[t], xp, yp, r, a, 7);
        row_sums(&three, types[t], xp, yp, r, b, 7);
        for (int j = 0; j < 7; j++) {
          ck_assert_double_eq_tol(a[j][0], b[j][0], TOL);
          ck_assert_double_eq_tol(a[j][1], b[j][1], TOL / one.dx);
          ck_assert_double_eq_tol(a[j][2], b[j][2], TOL / one.dy);
        }
      }
    }
}
END_TEST

/* A zero extent is the delta limit of the corner rule. */
START_TEST(t_ugimp_zero_extent)
{
  mpm_mesh m = make_mesh(7, 6, MPM_TOPO_T3, MPM_DIAG_MIRROR, 0, 1);
  const double r[4] = {0.0, 0.0, 0.0, 0.0};
  expect_same_as_delta(&m, m.x0 + 3.3 * m.dx, m.y0 + 0.8 * m.dy, r);
}
END_TEST

/* ------------------------------------------------------------ registry */

START_TEST(t_registry)
{
  ck_assert_ptr_eq(mpm_shape_lookup("delta"), &mpm_shape_delta);
  ck_assert_ptr_eq(mpm_shape_lookup("ugimp"), &mpm_shape_ugimp);
  ck_assert_ptr_eq(mpm_shape_lookup("cpdi"), &mpm_shape_cpdi);
  ck_assert_int_eq(mpm_shape_ugimp.convect, 0);
  ck_assert_int_eq(mpm_shape_cpdi.convect, 1);
  ck_assert_ptr_null(mpm_shape_lookup("bspline"));
  ck_assert_ptr_null(mpm_shape_lookup(""));
  ck_assert_ptr_null(mpm_shape_lookup("delta "));
  ck_assert_ptr_null(mpm_shape_lookup(NULL));
  int n = 0;
  for (const mpm_shape_type *const *t = mpm_shape_table; *t; t++, n++) {
    ck_assert_ptr_nonnull((*t)->name);
    ck_assert_ptr_nonnull((*t)->description);
    ck_assert_ptr_nonnull((*t)->eval);
    ck_assert_ptr_eq(mpm_shape_lookup((*t)->name), *t);  /* names unique */
  }
  ck_assert_int_eq(n, 3);
}
END_TEST

/* ------------------------------------------------------------- stencil */

/* Add a point at (x, y) with extent r. */
static size_t add_point(mpm_points *pts, double x, double y, const double r[4])
{
  size_t i;
  ck_assert_int_eq(mpm_points_push(pts, &i), MPM_OK);
  pts->x[i] = x;
  pts->y[i] = y;
  pts->r1x[i] = r[0];
  pts->r1y[i] = r[1];
  pts->r2x[i] = r[2];
  pts->r2y[i] = r[3];
  return i;
}

/* The stencil of a point store (its fill, in batches) is eval's point by
 * point, bit for bit, and each point's row is its centre's unit row: rotated
 * extents (the general rule) and extents along the axes of either sign (the
 * faster path, some of them clamped or wrapped), on every mesh kind,
 * periodic along x. */
START_TEST(t_stencil_matches_eval)
{
  uint64_t s = 42;
  for (int wide = 0; wide < 2; wide++)             /* 7 units, or a periodic x of one */
  for (int kind = 0; kind < 4; kind++)
    for (int aligned = 0; aligned < 2; aligned++) {
      mpm_mesh m = make_mesh(wide ? 7 : 1, 6, topo_of[kind], diag_of[kind], 1, 0);
      mpm_points *pts = mpm_points_alloc(0);
      ck_assert_ptr_nonnull(pts);
      for (int k = 0; k < 300; k++) {
        double r[4];
        random_extent(&m, &s, 0.1, 0.5, r);
        if (aligned) {
          r[0] = (0.05 + 0.45 * rnd(&s)) * m.dx * (k % 7 == 0 ? -1.0 : 1.0);
          r[1] = r[2] = 0.0;
          r[3] = (0.05 + 0.45 * rnd(&s)) * m.dy * (k % 5 == 0 ? -1.0 : 1.0);
        }
        add_point(pts, random_coord(&s, m.x0, m.lx, m.dx, 1, 0.0),
                  random_coord(&s, m.y0, m.ly, m.dy, 0, 0.0), r);
      }
      mpm_shape_stencil *st = mpm_shape_stencil_alloc(0);
      ck_assert_ptr_nonnull(st);
      mpm_err err = {0};
      for (int pass = 0; pass < 2; pass++) {  /* grow, then reuse */
        ck_assert_int_eq(mpm_shape_stencil_compute(st, &mpm_shape_ugimp, &m, pts, 0.5, &err),
                         MPM_OK);
        ck_assert_uint_ge(st->cap, pts->n);
        for (size_t p = 0; p < pts->n; p++) {
          const double r[4] = {pts->r1x[p], pts->r1y[p], pts->r2x[p], pts->r2y[p]};
          int node[MPM_STENCIL_W];
          double S[MPM_STENCIL_W], gx[MPM_STENCIL_W], gy[MPM_STENCIL_W];
          const int n = plane_eval(&mpm_shape_ugimp, &m, pts->x[p], pts->y[p], r, node, S, gx, gy);
          ck_assert_int_eq(st->count[p], n);
          int i, j;
          double u, v;
          ck_assert_int_eq(plane_locate(&m, pts->x[p], pts->y[p], &i, &j, &u, &v), 0);
          ck_assert_int_eq(st->row[p], j);
          const size_t o = p * (size_t)st->w;
          for (int k = 0; k < n; k++) {
            ck_assert_int_eq(st->node[o + k], node[k]);
            ck_assert(st->S[o + k] == S[k]);  /* same arithmetic: bit-identical */
            ck_assert(st->dS[0][o + k] == gx[k]);
            ck_assert(st->dS[1][o + k] == gy[k]);
          }
        }
      }
      mpm_points_free(pts);
      mpm_shape_stencil_free(st);
    }
  mpm_shape_stencil_free(NULL);
}
END_TEST

START_TEST(t_stencil_outside)
{
  mpm_mesh m;
  memset(&m, 0, sizeof m);
  m.nx = 10;
  m.ny = 4;
  m.dx = m.dy = 0.25;
  mpm_err err = {0};
  ck_assert_int_eq(mpm_mesh_setup(&m, &err), MPM_OK);
  mpm_points *pts = mpm_points_alloc(4);
  const double r[4] = {0.05, 0.0, 0.0, 0.05};
  for (int k = 0; k < 40; k++)
    add_point(pts, 0.1 + 0.05 * k, 0.5, r);
  pts->id[25] = 17;                     /* ids are not indices */
  pts->y[25] = -0.002;
  pts->x[25] = 1.234;
  pts->x[31] = 2.6;                     /* a second, later offender */
  mpm_shape_stencil *st = mpm_shape_stencil_alloc(8);
  for (int v = 0; v < 2; v++) {
    const mpm_shape_type *type = v ? &mpm_shape_ugimp : &mpm_shape_delta;
    mpm_err_clear(&err);
    ck_assert_int_eq(mpm_shape_stencil_compute(st, type, &m, pts, 0.031, &err), MPM_EOUTSIDE);
    ck_assert_int_eq(err.code, MPM_EOUTSIDE);
    ck_assert_msg(strstr(err.msg, "point 17 ") != NULL, "%s", err.msg);
    ck_assert_msg(strstr(err.msg, "(1.234, -0.002) m") != NULL, "%s", err.msg);
    ck_assert_msg(strstr(err.msg, "t = 0.031 s") != NULL, "%s", err.msg);
  }
  pts->y[25] = 0.5;                     /* now only the second one */
  ck_assert_int_eq(mpm_shape_stencil_compute(st, &mpm_shape_ugimp, &m, pts, 0.5, &err),
                   MPM_EOUTSIDE);
  char want[32];
  snprintf(want, sizeof want, "point %d ", pts->id[31]);
  ck_assert_msg(strstr(err.msg, want) != NULL, "%s", err.msg);
  pts->x[31] = 2.5;                     /* exactly on the right edge: inside */
  mpm_err_clear(&err);
  ck_assert_int_eq(mpm_shape_stencil_compute(st, &mpm_shape_ugimp, &m, pts, 0.5, &err), MPM_OK);
  ck_assert_int_eq(err.code, MPM_OK);
  mpm_points_free(pts);
  mpm_shape_stencil_free(st);
}
END_TEST

START_TEST(t_stencil_empty)
{
  mpm_mesh m = make_mesh(7, 6, MPM_TOPO_Q4, MPM_DIAG_SLASH, 0, 0);
  mpm_points *pts = mpm_points_alloc(0);
  mpm_shape_stencil *st = mpm_shape_stencil_alloc(0);
  mpm_err err = {0};
  ck_assert_int_eq(mpm_shape_stencil_compute(st, &mpm_shape_delta, &m, pts, 0.0, &err), MPM_OK);
  mpm_points_free(pts);
  mpm_shape_stencil_free(st);
}
END_TEST

int main(void)
{
  Suite *s = suite_create("shape");
  TCase *tc = tcase_create("shape");
  tcase_set_timeout(tc, 60);
  tcase_add_test(tc, t_invariants_delta);
  tcase_add_test(tc, t_invariants_ugimp);
  tcase_add_test(tc, t_invariants_ugimp_wide);
  tcase_add_test(tc, t_ugimp_axes_bitwise);
  tcase_add_test(tc, t_invariants_cpdi);
  tcase_add_test(tc, t_cpdi_convect);
  tcase_add_test(tc, t_ugimp_inside_one_element);
  tcase_add_test(tc, t_ugimp_hand_values);
  tcase_add_test(tc, t_ugimp_clamped);
  tcase_add_test(tc, t_ugimp_periodic_wrap);
  tcase_add_test(tc, t_ugimp_zero_extent);
  tcase_add_test(tc, t_one_unit_periodic);
  tcase_add_test(tc, t_registry);
  tcase_add_test(tc, t_stencil_matches_eval);
  tcase_add_test(tc, t_stencil_outside);
  tcase_add_test(tc, t_stencil_empty);
  suite_add_tcase(s, tc);
  SRunner *sr = srunner_create(s);
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf ? EXIT_FAILURE : EXIT_SUCCESS;
}
