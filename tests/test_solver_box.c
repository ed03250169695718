/* test_solver_box.c: the step on a mesh of boxes (mesh.nz > 0) from its
 * equations.
 *
 *  - free flight: a periodic box of elastic points moving as a rigid body
 *    keeps every velocity and a zero stress (the weights are a partition of
 *    unity and their gradients sum to zero: sum S v_i = v, L = 0), and moves
 *    by v t;
 *  - free fall: with gravity (gx, gy, gz) and no wall every point falls with
 *    v = g t (the body-force lanes of the nodal records);
 *  - momentum: a periodic box with a random velocity field keeps its total
 *    momentum to round-off while it deforms (sum_i f_i = 0: internal forces
 *    cancel when sum_i gradS_ip = 0, the force rows of a symmetric stress
 *    assembled consistently; FLIP returns sum_i m_i a_i = sum_i f_i);
 *  - the plane: a z-invariant 3D run (periodic z, no z motion) gives the
 *    plane run of the same input, to round-off, with every shape;
 *  - the element dilatation (Q1/P0 boxes): a uniform pressure pushes no
 *    interior node, and the projection returns a linear mean stress exactly
 *    and keeps the box means of any other;
 *  - the affine transfer (APIC): every test above under it too; an affine
 *    velocity field is carried exactly through a step, C_p included, and a
 *    periodic box shifted by one unit along every axis gives the shifted
 *    result (the offsets x_i - x_p take each node's nearest image);
 *  - a blow-up is named from the 3D fields: the point, the field, its value,
 *    the position (x, y, z), the time, and the likely cause judged with dz
 *    (the stable step, the NGF diffusion limit).
 * The looped tests run _i % 3 over the shapes and _i / 3 over FLIP, APIC.
 * (That the step does not depend on the number of threads: test_threads.c.) */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/config.h"
#include "material/hyper.h"
#include "nonlocal/grid.h"
#include "solver/solver.h"
#include "sim_config.h"

static mpm_sim *make(const mpm_config *c)
{
  mpm_sim *s = NULL;
  mpm_err err = {0};
  ck_assert_msg(mpm_sim_create(&s, c, &err) == MPM_OK, "%s", err.msg);
  ck_assert_int_eq(s->dim, c->mesh.nz > 0 ? 3 : 2);
  return s;
}

static void steps(mpm_sim *s, int n)
{
  mpm_err err = {0};
  for (int k = 0; k < n; k++)
    ck_assert_msg(mpm_sim_step(s, &err) == MPM_OK, "%s", err.msg);
}

static const char *const shapes[] = {"delta", "ugimp", "cpdi"};

/* Loop index _i: the shape _i % 3 under FLIP (_i < 3) or APIC. */
static void loop_scheme(mpm_config *c, int i)
{
  c->time.transfer = i < 3 ? MPM_TRANSFER_FLIP : MPM_TRANSFER_APIC;
}

START_TEST(t_free_flight)
{
  mpm_config c;
  sim_config_box(&c, shapes[_i % 3], 4, 4, 4);
  loop_scheme(&c, _i);
  c.fill[0].vx = 0.3;
  c.fill[0].vy = -0.2;
  c.fill[0].vz = 0.1;
  mpm_sim *s = make(&c);
  const mpm_points *P = s->pts;
  ck_assert_int_eq((int)P->n, 512);
  double *x0 = malloc(3 * P->n * sizeof *x0);
  for (size_t p = 0; p < P->n; p++) {
    x0[3 * p] = P->x[p];
    x0[3 * p + 1] = P->y[p];
    x0[3 * p + 2] = P->z[p];
  }
  steps(s, 20);
  const double t = s->t, v[3] = {0.3, -0.2, 0.1}, len = 0.04;
  for (size_t p = 0; p < P->n; p++) {
    /* velocities to round-off of the sums (1e-15 of v), stress zero to
     * the round-off of L = sum v_i (x) gradS = 0 (1e-13 of v/dx, times
     * E dt per step) */
    ck_assert_double_eq_tol(P->vx[p], v[0], 1e-14);
    ck_assert_double_eq_tol(P->vy[p], v[1], 1e-14);
    ck_assert_double_eq_tol(P->vz[p], v[2], 1e-14);
    ck_assert_double_le(fabs(P->sxx[p]) + fabs(P->syz[p]) + fabs(P->szx[p]), 1e-6);
    const double *const now[3] = {P->x, P->y, P->z};
    for (int d = 0; d < 3; d++) {
      double dx = now[d][p] - (x0[3 * p + d] + v[d] * t);
      dx -= len * nearbyint(dx / len);          /* periodic */
      ck_assert_double_le(fabs(dx), 1e-12);
    }
  }
  free(x0);
  mpm_sim_free(s);
}
END_TEST

START_TEST(t_free_fall)
{
  mpm_config c;
  sim_config_box(&c, shapes[_i % 3], 4, 8, 4);
  loop_scheme(&c, _i);
  c.bc.left = c.bc.right = c.bc.bottom = c.bc.top = MPM_BC_FREE;
  c.bc.front = c.bc.back = MPM_BC_FREE;
  c.fill[0].xmin = c.fill[0].ymin = c.fill[0].zmin = 0.01;
  c.fill[0].xmax = c.fill[0].zmax = 0.03;
  c.fill[0].ymax = 0.07;
  c.gravity.gx = 1.0;
  c.gravity.gy = -9.8;
  c.gravity.gz = 0.5;
  mpm_sim *s = make(&c);
  /* under APIC the points a quarter unit along z, so that a layer of them
   * lies on the grid plane z = 0.03 m with empty nodes beyond it, where
   * delta's gradients do not vanish (transfer.inc, mpm_tr_gather_empty);
   * FLIP keeps [DK15]'s L_p, whose stress such a layer would feel */
  for (size_t p = 0; _i >= 3 && p < s->pts->n; p++)
    s->pts->z[p] = 0.0025 * nearbyint((s->pts->z[p] + 0.0025) / 0.0025);
  steps(s, 10);          /* 10 dt: the box moves 0.3 mm */
  const mpm_points *P = s->pts;
  const double t = s->t;
  for (size_t p = 0; p < P->n; p++) {
    ck_assert_double_eq_tol(P->vx[p], 1.0 * t, 1e-13);
    ck_assert_double_eq_tol(P->vy[p], -9.8 * t, 1e-13);
    ck_assert_double_eq_tol(P->vz[p], 0.5 * t, 1e-13);
  }
  mpm_sim_free(s);
}
END_TEST

/* A reproducible velocity field of amplitude 0.05 m/s. */
static double noise(unsigned *state)
{
  *state = *state * 1103515245u + 12345u;
  return 0.05 * ((double)(*state >> 8 & 0xffff) / 65535.0 - 0.5);
}

START_TEST(t_momentum)
{
  mpm_config c;
  sim_config_box(&c, shapes[_i % 3], 4, 4, 4);
  loop_scheme(&c, _i);
  mpm_sim *s = make(&c);
  mpm_points *P = s->pts;
  unsigned st = 12345u;
  double p0[3] = {0.0, 0.0, 0.0}, scale = 0.0;
  for (size_t p = 0; p < P->n; p++) {
    P->vx[p] = noise(&st);
    P->vy[p] = noise(&st);
    P->vz[p] = noise(&st);
    p0[0] += P->mass[p] * P->vx[p];
    p0[1] += P->mass[p] * P->vy[p];
    p0[2] += P->mass[p] * P->vz[p];
    scale += P->mass[p] * 0.05;
  }
  steps(s, 50);
  double p1[3] = {0.0, 0.0, 0.0}, smax = 0.0;
  for (size_t p = 0; p < P->n; p++) {
    p1[0] += P->mass[p] * P->vx[p];
    p1[1] += P->mass[p] * P->vy[p];
    p1[2] += P->mass[p] * P->vz[p];
    smax = fmax(smax, fabs(P->sxy[p]) + fabs(P->syz[p]) + fabs(P->szx[p]));
  }
  ck_assert_double_gt(smax, 1.0);              /* it deformed: shear stresses of > 1 Pa */
  for (int d = 0; d < 3; d++)                  /* 1e-13 of m |v|: round-off of 50 steps */
    ck_assert_double_le(fabs(p1[d] - p0[d]), 1e-13 * scale);
  mpm_sim_free(s);
}
END_TEST

/* The plane run and its z-invariant 3D counterpart (above) agree; with
 * ramp, the column runs into a frictionless 45 degree ramp, a wall polygon
 * (in 3D its prism along z), whose nodes at the open units hold only the
 * normal of the side. */
static void plane_and_3d(int i, int ramp)
{
  mpm_config c2, c3;
  const int nz = i < 3 ? 2 : 4;                 /* uGIMP's APIC: 4 units on a periodic axis */
  sim_config_column(&c2, shapes[i % 3], 0, "mu_i");
  sim_config_column(&c3, shapes[i % 3], nz, "mu_i");
  loop_scheme(&c2, i);
  loop_scheme(&c3, i);
  if (ramp) {
    mpm_config *cs[2] = {&c2, &c3};
    const double px[3] = {0.05, 0.12, 0.12}, py[3] = {0.0, 0.0, 0.07};
    for (int k = 0; k < 2; k++) {
      cs[k]->wall.nvert = 3;
      memcpy(cs[k]->wall.px, px, sizeof px);
      memcpy(cs[k]->wall.py, py, sizeof py);
      cs[k]->wall.kind = MPM_BC_FRICTIONLESS;
    }
  }
  mpm_sim *s2 = make(&c2), *s3 = make(&c3);
  if (ramp) {                                   /* oblique nodes: the normal alone, not z */
    int oblique = 0;
    for (int id = 0; id < s3->mesh.nnodes; id++) {
      const unsigned char f = s3->bc.fix[id];
      if ((f & MPM_FIX_N) && (f & (MPM_FIX_X | MPM_FIX_Y | MPM_FIX_Z)) == 0)
        oblique++;                              /* the ramp's foot also has the floor's */
    }
    ck_assert_int_ge(oblique, 4 * nz);
  }
  ck_assert_double_eq(s2->dt, s3->dt);
  const int n = ramp ? 800 : 200;               /* the front reaches the ramp after 0.1 s */
  steps(s2, n);
  steps(s3, n);
  const mpm_points *P = s2->pts, *Q = s3->pts;
  ck_assert_uint_eq(Q->n, 2 * (size_t)nz * P->n);  /* 2 points a unit along z */
  double vmax = 0.0, dev = 0.0, wz = 0.0, pmax = 0.0, dp = 0.0, xmax = 0.0;
  for (size_t q = 0; q < Q->n; q++) {
    size_t best = 0;                           /* the plane point at the same (x, y) */
    double dbest = INFINITY;
    for (size_t p = 0; p < P->n; p++) {
      const double d = fabs(P->x[p] - Q->x[q]) + fabs(P->y[p] - Q->y[q]);
      if (d < dbest) {
        dbest = d;
        best = p;
      }
    }
    vmax = fmax(vmax, hypot(P->vx[best], P->vy[best]));
    xmax = fmax(xmax, Q->x[q]);
    dev = fmax(dev, fabs(P->vx[best] - Q->vx[q]) + fabs(P->vy[best] - Q->vy[q]));
    wz = fmax(wz, fabs(Q->vz[q]));
    pmax = fmax(pmax, fabs(P->syy[best]));
    dp = fmax(dp, fabs(P->syy[best] - Q->syy[q]) + fabs(P->szz[best] - Q->szz[q]));
    ck_assert_int_eq(P->state[best], Q->state[q]);
    ck_assert_double_le(dbest, 1e-12);
  }
  ck_assert_double_gt(vmax, 0.01);             /* it flows */
  if (ramp)                                    /* and climbs the ramp (foot 0.05 m) */
    ck_assert_msg(xmax > 0.06, "front at %g m", xmax);
  ck_assert_double_le(dev, 1e-9 * vmax);        /* round-off of 200 steps, not a scheme's */
  ck_assert_double_le(wz, 1e-12 * vmax);
  ck_assert_double_le(dp, 1e-9 * pmax);
  mpm_sim_free(s2);
  mpm_sim_free(s3);
}

START_TEST(t_plane)
{
  plane_and_3d(_i, 0);
}
END_TEST

/* uGIMP and CPDI1 under FLIP and APIC: over the 800 steps the ramp needs,
 * delta weights make the two runs part by round-off already without it (a
 * point's unit flips on a boundary; 1e-6 m apart at the end). */
START_TEST(t_plane_ramp)
{
  static const int scheme[4] = {1, 2, 4, 5};
  plane_and_3d(scheme[_i], 1);
}
END_TEST

/* A box of 6 x 6 x 6 units of 1 cm with no-slip walls, filled 4 cm deep,
 * under gravity, with a square orifice [from, to]^2 in its floor open from
 * the start. */
static void draining_box(mpm_config *c, const char *model, double from, double to)
{
  sim_config_box(c, "ugimp", 6, 6, 6);
  sim_config_material(c, model, 1e6);
  c->bc.left = c->bc.right = c->bc.bottom = c->bc.front = c->bc.back = MPM_BC_NOSLIP;
  c->bc.top = MPM_BC_FREE;
  c->gravity.gy = -9.8;
  c->fill[0].ymax = 0.04;
  c->outlet.edge = MPM_OUTLET_BOTTOM;
  c->outlet.closed = MPM_BC_NOSLIP;
  c->outlet.from = c->outlet.from2 = from;
  c->outlet.to = c->outlet.to2 = to;
}

/* A box draining through a square orifice in its floor (a disc with
 * _i = 1; _i = 2, 3: the square and a wider disc under the hyperelastic
 * NGF): points leave only through it, and the mass in the box plus the
 * mass removed stays the initial mass. Under NGF the open orifice is a
 * free surface for g: the field's open faces are the units of the floor
 * whose four corners it frees (mpm_bc_outlet_faces, and for the disc
 * mpm_bc_outlet_face_open unit by unit), and every g stays finite and
 * >= 0. _i = 4: the square under the NGF with the extent rule
 * (material.g_average = "extent"). */
START_TEST(t_outlet)
{
  mpm_config c;
  draining_box(&c, _i >= 2 ? "ngf_hyper" : "mu_i", 0.02, 0.04);
  c.outlet.shape = _i % 2 ? MPM_OUTLET_DISC : MPM_OUTLET_RECTANGLE;
  if (_i == 4)
    c.material.g_average = MPM_NONLOCAL_EXTENT;
  if (_i == 3) {                                /* a disc of radius 2.5 cm round (3, 3) cm */
    c.outlet.from = c.outlet.from2 = 0.005;
    c.outlet.to = c.outlet.to2 = 0.055;
  }
  mpm_sim *s = make(&c);
  const double m0 = s->mass0;
  steps(s, 300);
  const mpm_points *P = s->pts;
  ck_assert_int_gt(s->nremoved, 10);
  const mpm_nonlocal_grid *g = s->nl ? &s->nl->grid : NULL;
  ck_assert_int_eq(g != NULL, _i >= 2);
  if (g) {
    int lo[3], hi[3];
    ck_assert_int_eq(mpm_bc_outlet_faces(&s->bc, &s->mesh, lo, hi), MPM_FACE_YLO);
    ck_assert_int_eq(g->open_face, MPM_FACE_YLO);
    /* the square: floor units 2, 3 along x and z (0.02 ... 0.04 m); the
     * disc: units 1 ... 4, of which the 12 whose four corners lie within
     * 2.5 cm of the centre (not the 4 corner units: 2.83 cm) */
    const int u0 = _i == 3 ? 1 : 2, u1 = _i == 3 ? 5 : 4;
    for (int a = 0; a < 3; a++) {
      ck_assert_int_eq(g->open_lo[a], a == 1 ? 0 : u0);
      ck_assert_int_eq(g->open_hi[a], a == 1 ? 6 : u1);
      ck_assert_int_eq(g->open_lo[a], lo[a]);
      ck_assert_int_eq(g->open_hi[a], hi[a]);
    }
    int cu[3] = {0, 0, 0}, open = 0;
    for (cu[2] = u0; cu[2] < u1; cu[2]++)
      for (cu[0] = u0; cu[0] < u1; cu[0]++) {
        const size_t e = mpm_nonlocal_grid_index(g, cu);
        const int o = mpm_bc_outlet_face_open(&s->bc, &s->mesh, cu);
        const double none = 0.0;               /* beyond the floor: sm is not read */
        size_t nb;
        /* the floor's rule for g: zero flux (+1) on an open face, g = 0 (-1) */
        ck_assert_int_eq(mpm_nonlocal_grid_side(g, &none, cu, e, MPM_FACE_YLO, &nb), o ? 1 : -1);
        open += o;
      }
    ck_assert_int_eq(open, _i == 3 ? 12 : 4);
    ck_assert_int_eq(g->open_mask != NULL, _i == 3);
    int fluid = 0;
    for (size_t p = 0; p < P->n; p++) {
      ck_assert(isfinite(P->g[p]) && P->g[p] >= 0.0);
      fluid += P->g[p] > 0.0;
    }
    ck_assert_int_gt(fluid, 10);
  }
  double m = 0.0;
  for (size_t p = 0; p < P->n; p++) {
    m += P->mass[p];
    ck_assert(P->y[p] >= 0.0 && P->x[p] >= 0.0 && P->x[p] <= 0.06 && P->z[p] >= 0.0 &&
              P->z[p] <= 0.06);
  }
  ck_assert_uint_eq(P->n + (size_t)s->nremoved, 6 * 4 * 6 * 8);
  ck_assert_double_eq_tol(m + s->mass_removed, m0, 1e-13 * m0);
  mpm_sim_free(s);
}
END_TEST

/* Max |v| over the points. */
static double max_speed(const mpm_points *P)
{
  double v = 0.0;
  for (size_t p = 0; p < P->n; p++) {
    const double s = sqrt(P->vx[p] * P->vx[p] + P->vy[p] * P->vy[p] + P->vz[p] * P->vz[p]);
    v = s > v ? s : v;
  }
  return v;
}

/* A lithostatic fill in 3D (fill.lithostatic): a column 6 cm high in a
 * mesh of 8 units of 1 cm, periodic along x and z, on a rough floor. Every point starts with
 * sigma_yy = rho g (y - H) (H the fill's top), sigma_xx = sigma_zz =
 * K0 sigma_yy, K0 = nu / (1 - nu), and its mass times exp(p/K). The
 * column is then in equilibrium under gravity: after 200 steps it moves at
 * under 0.1 % of the speed the same column reaches from zero stress (2e-4
 * and 1e-4 measured: the discrete balance at the floor and the surface).
 * Elastic (_i = 0) and under the hyperelastic NGF (_i = 1; nu = 0.45, so
 * K0 puts mu below mu_s), where F is the elastic state of that stress: the
 * Hencky stress of F equals it. */
START_TEST(t_lithostatic)
{
  double speed[2];
  for (int pre = 1; pre >= 0; pre--) {
    mpm_config c;
    sim_config_box(&c, "ugimp", 2, 8, 2);
    sim_config_material(&c, _i ? "ngf_hyper" : "elastic", 1e6);
    c.material.nu = _i ? 0.45 : 0.3;
    c.bc.bottom = MPM_BC_NOSLIP;
    c.bc.top = MPM_BC_FREE;
    c.gravity.gy = -9.8;
    c.fill[0].ymax = 0.06;
    c.fill[0].lithostatic = pre;
    mpm_sim *s = make(&c);
    const mpm_points *P = s->pts;
    const double k0 = c.material.nu / (1.0 - c.material.nu), K = s->par.K;
    const double V = 0.005 * 0.005 * 0.005;
    for (size_t p = 0; pre && p < P->n; p++) {
      const double syy = 1500.0 * -9.8 * (0.06 - P->y[p]), pr = -(1.0 + 2.0 * k0) * syy / 3.0;
      const mpm_sym3 sig = {k0 * syy, syy, k0 * syy, 0.0, 0.0, 0.0};
      ck_assert_double_eq_tol(P->syy[p], syy, 1e-12 * 900.0);
      ck_assert_double_eq_tol(P->sxx[p], k0 * syy, 1e-12 * 900.0);
      ck_assert_double_eq_tol(P->szz[p], k0 * syy, 1e-12 * 900.0);
      ck_assert_double_eq_tol(P->mass[p], 1500.0 * V * exp(pr / K), 1e-15 * 1500.0 * V);
      if (_i) {
        const mpm_mat3 F = {{{P->fxx[p], P->fxy[p], P->fxz[p]}, {P->fyx[p], P->fyy[p],
                              P->fyz[p]}, {P->fzx[p], P->fzy[p], P->fzz[p]}}};
        const mpm_mat3 I = {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
        const mpm_sym3 h = mpm_material_hyper_stress(&s->par, &F, &I);
        ck_assert_double_eq_tol(h.yy, sig.yy, 1e-9 * 900.0);
        ck_assert_double_eq_tol(h.xx, sig.xx, 1e-9 * 900.0);
        ck_assert_double_eq_tol(h.zz, sig.zz, 1e-9 * 900.0);
        ck_assert(fabs(h.xy) + fabs(h.yz) + fabs(h.zx) <= 1e-9 * 900.0);
      }
    }
    steps(s, 200);
    speed[pre] = max_speed(P);
    mpm_sim_free(s);
  }
  ck_assert_msg(speed[1] < 1e-3 * speed[0], "%g against %g m/s", speed[1], speed[0]);
}
END_TEST

/* absorb ([DK-silo] 7.1) in 3D: after a step, a point at or above the line
 * that moves up has its vy scaled by the factor; a point below it, or moving
 * down, keeps its velocity (a stress-free periodic box under no gravity:
 * the first step's nodal forces vanish, so FLIP leaves every velocity as it
 * was). Points at y = 2.5, 7.5, 12.5 and 17.5 mm, the line at 10 mm. */
START_TEST(t_absorb_layer)
{
  const double factor[2] = {0.0, 0.5};
  for (int k = 0; k < 2; k++) {
    mpm_config c;
    sim_config_box(&c, shapes[_i], 2, 2, 2);
    c.absorb.above = 0.01;
    c.absorb.factor = factor[k];
    mpm_sim *s = make(&c);
    mpm_points *P = s->pts;
    ck_assert_uint_eq(P->n, 64);
    for (size_t p = 0; p < P->n; p++) {
      P->vx[p] = 0.3;
      P->vy[p] = (P->id[p] & 1) ? 0.2 : -0.2; /* up and down in every row */
      P->vz[p] = -0.1;
    }
    steps(s, 1);
    int scaled = 0;
    for (size_t p = 0; p < P->n; p++) {
      const int high = P->y[p] >= 0.01, up = (int)(P->id[p] & 1);
      const double vy = up ? 0.2 : -0.2;
      scaled += high && up;
      ck_assert_double_eq_tol(P->vy[p], high && up ? factor[k] * vy : vy, 1e-12);
      ck_assert_double_eq_tol(P->vx[p], 0.3, 1e-12);
      ck_assert_double_eq_tol(P->vz[p], -0.1, 1e-12);
    }
    ck_assert_int_eq(scaled, 16);
    mpm_sim_free(s);
  }
}
END_TEST

/* material.state_density under the hyperelastic NGF: a column filled at
 * rho_c collapses. With "unit" every dense point lies in a box whose
 * points' mass over their volume, sum m / sum V, is at least rho_c, and
 * some dense points are below rho_c on their own; with "point" no point
 * below rho_c is dense (_i = 0: unit, 1: point). */
START_TEST(t_hyper_state_density)
{
  mpm_config c;
  sim_config_column(&c, "ugimp", 2, "ngf_hyper");
  c.material.state_density = _i ? MPM_DENSITY_POINT : MPM_DENSITY_UNIT;
  c.material.rho_c = 1500.0;                    /* the fill's density */
  mpm_sim *s = make(&c);
  const mpm_points *P = s->pts;
  const mpm_mesh *m = &s->mesh;
  const size_t nu = (size_t)m->nx * m->ny * m->nz;
  double *sm = malloc(nu * sizeof *sm), *sv = malloc(nu * sizeof *sv);
  size_t *unit = malloc(P->n * sizeof *unit);
  int lone = 0, dense = 0;
  for (int k = 0; k < 100; k++) {
    steps(s, 1);
    for (size_t e = 0; e < nu; e++)
      sm[e] = sv[e] = 0.0;
    for (size_t p = 0; p < P->n; p++) {
      const double x[3] = {P->x[p], P->y[p], P->z[p]};
      int u[3];
      double l[3];
      ck_assert_int_eq(mpm_mesh_locate(m, x, u, l), 0);
      unit[p] = (size_t)u[0] + (size_t)m->nx * (u[1] + (size_t)m->ny * u[2]);
      sm[unit[p]] += P->mass[p];
      sv[unit[p]] += P->vol[p];
    }
    for (size_t p = 0; p < P->n; p++) {
      if (P->state[p] != MPM_STATE_DENSE)
        continue;
      dense++;
      const int below = P->mass[p] / P->vol[p] < 1500.0;
      lone += below;
      if (_i == 0)
        ck_assert_double_ge(sm[unit[p]] / sv[unit[p]], 1500.0 * (1.0 - 1e-12));
      else
        ck_assert(!below);
    }
  }
  ck_assert_int_gt(dense, 1000);
  if (_i == 0)
    ck_assert_int_gt(lone, 0);
  free(sm);
  free(sv);
  free(unit);
  mpm_sim_free(s);
}
END_TEST

/* stop.mass in 3D: the box of t_outlet run by mpm_sim_run stops once the
 * mass left in it (kg) falls below half the initial, with that mass as the
 * stop value. */
START_TEST(t_stop_mass)
{
  mpm_config c;
  draining_box(&c, "mu_i", 0.0, 0.06);         /* the whole floor opens: free fall */
  c.stop.mass = 0.5 * 1500 * 0.06 * 0.04 * 0.06;
  c.region.xmin = c.region.ymin = -1e9;       /* the input's default region: all */
  c.region.xmax = c.region.ymax = 1e9;
  c.time.t_end = 1.0;
  mpm_sim *s = make(&c);
  mpm_err err = {0};
  ck_assert_msg(mpm_sim_run(s, NULL, &err) == MPM_OK, "%s", err.msg);
  ck_assert_int_eq(s->stop, MPM_STOP_MASS);
  ck_assert(s->t < 0.2);                      /* free fall through 2 cm: about 0.06 s */
  double m = 0.0;
  for (size_t p = 0; p < s->pts->n; p++)
    m += s->pts->mass[p];
  ck_assert(m < c.stop.mass && m > 0.0);
  ck_assert_double_eq(s->stop_value, m);
  mpm_sim_free(s);
}
END_TEST

/* The unit options (material.state_density = "unit", mesh.dilatation =
 * "unit": B-bar with one mean stress per box): a settling column keeps its
 * momentum balance (the modified stress is still an internal force: the box
 * falls with g while nothing touches the floor) and after every step the
 * dense points of a box share one mean stress (sxx + syy + szz)/3. */
START_TEST(t_unit_options)
{
  mpm_config c;
  sim_config_column(&c, "ugimp", 2, "mu_i");
  c.material.state_density = MPM_DENSITY_UNIT;
  c.mesh.dilatation = MPM_DILATATION_UNIT;
  mpm_sim *s = make(&c);
  const mpm_points *P = s->pts;
  const mpm_mesh *m = &s->mesh;
  const size_t nu = (size_t)m->nx * m->ny * m->nz;
  double *first = malloc(nu * sizeof *first);
  for (int k = 0; k < 60; k++) {
    steps(s, 1);
    for (size_t e = 0; e < nu; e++)
      first[e] = NAN;
    double pmax = 0.0, dev = 0.0;
    int shared = 0;
    for (size_t p = 0; p < P->n; p++) {
      if (P->state[p] != MPM_STATE_DENSE)
        continue;
      const double x[3] = {P->x[p], P->y[p], P->z[p]};
      int u[3];
      double l[3];
      ck_assert_int_eq(mpm_mesh_locate(m, x, u, l), 0);
      const size_t e = (size_t)u[0] + (size_t)m->nx * (u[1] + (size_t)m->ny * u[2]);
      const double sm = (P->sxx[p] + P->syy[p] + P->szz[p]) / 3.0;
      pmax = fmax(pmax, fabs(sm));
      if (isnan(first[e]))
        first[e] = sm;
      else {
        dev = fmax(dev, fabs(sm - first[e]));
        shared++;
      }
    }
    if (k == 59)                /* settled: most points dense, several a box */
      ck_assert_int_gt(shared, 100);
    ck_assert_double_le(dev, 1e-12 * pmax);
  }
  double pz = 0.0, mtot = 0.0;
  for (size_t p = 0; p < P->n; p++) {
    pz += P->mass[p] * P->vz[p];
    mtot += P->mass[p];
  }
  ck_assert_double_le(fabs(pz), 1e-12 * mtot);  /* nothing pushes along the periodic z */
  free(first);
  mpm_sim_free(s);
}
END_TEST

/* mesh.dilatation = "element" on boxes: a 4 x 4 x 4 mesh of 1 cm boxes,
 * walled on every face and filled with 2 x 2 x 2 points a box (every box
 * filled), delta weights; unless regular the points are moved off their
 * symmetric places and given unequal volumes. */
static mpm_sim *element_box(int rule, int regular, double dt)
{
  mpm_config c;
  sim_config_box(&c, "delta", 4, 4, 4);
  c.bc.left = c.bc.right = c.bc.bottom = c.bc.top = MPM_BC_NOSLIP;
  c.bc.front = c.bc.back = MPM_BC_NOSLIP;
  c.time.dt = dt;
  c.mesh.dilatation = rule;
  mpm_sim *s = make(&c);
  ck_assert_uint_eq(s->pts->n, 512);
  for (size_t p = 0; !regular && p < s->pts->n; p++) {
    s->pts->x[p] += (p % 3 == 0) ? 0.0011 : 0.0;
    s->pts->y[p] -= (p % 4 == 1) ? 0.0007 : 0.0;
    s->pts->z[p] += (p % 5 == 2) ? 0.0009 : 0.0;
    s->pts->vol[p] *= 1.0 + 0.5 * (double)(p % 2);
  }
  return s;
}

static void set_isotropic3(mpm_sim *s, size_t p, double sm)
{
  mpm_points *P = s->pts;
  P->sxx[p] = P->syy[p] = P->szz[p] = sm;
  P->sxy[p] = P->syz[p] = P->szx[p] = 0.0;
}

/* A uniform pressure exerts no force on an interior node when the filled
 * boxes act as Q1/P0 elements (the eight boxes' integrals of grad N_i
 * cancel), whatever the points' places and volumes; the point sums of the
 * "unit" rule do not cancel for the same points. Scale: p dy dz / m_node =
 * 1000 * 1e-4 / 1.5e-3 = 67 m/s^2. */
START_TEST(t_element_uniform)
{
  const int rules[2] = {MPM_DILATATION_ELEMENT, MPM_DILATATION_UNIT};
  for (int r = 0; r < 2; r++) {
    mpm_sim *s = element_box(rules[r], 0, 1e-6);
    for (size_t p = 0; p < s->pts->n; p++)
      set_isotropic3(s, p, -1000.0);
    steps(s, 1);
    double worst = 0.0;
    for (int k = 1; k < 4; k++)
      for (int j = 1; j < 4; j++)
        for (int i = 1; i < 4; i++) {
          const double *a = mpm_sim_node(s, mpm_mesh_node(&s->mesh, i, j, k)) + 3;
          worst = fmax(worst, sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]));
        }
    if (r == 0)
      ck_assert_double_le(worst, 1e-12 * 67.0);
    else
      ck_assert_double_ge(worst, 1e-2 * 67.0);
    mpm_sim_free(s);
  }
}
END_TEST

/* The force of box pressures P_e on an interior node N = (I, J, K) is
 * f = -sum_e P_e int_e grad N_N dV, int_e dN/dx_d = +-dy dz / 4 (the face
 * normal to d over 4; sign: the side of e on which N lies), so
 * f_d = A (sum of P_e over the four boxes above N along d - the four
 * below). Each box's points carry one isotropic stress (no deviator) and
 * are regular (their centroid the box centre, where the element takes its
 * pressure), so this is all of f_N = m_N a_N. */
static double box_stress_of(int e)
{
  return -1000.0 - 150.0 * (double)((e * 7) % 11);
}

START_TEST(t_element_forces)
{
  mpm_sim *s = element_box(MPM_DILATATION_ELEMENT, 1, 1e-6);
  const mpm_points *P = s->pts;
  for (size_t p = 0; p < P->n; p++) {
    const double x[3] = {P->x[p], P->y[p], P->z[p]};
    int u[3];
    double l[3];
    ck_assert_int_eq(mpm_mesh_locate(&s->mesh, x, u, l), 0);
    set_isotropic3(s, p, box_stress_of(u[0] + 4 * (u[1] + 4 * u[2])));
  }
  steps(s, 1);
  const double A = 0.01 * 0.01 / 4.0;
  double fmax_ = 0.0;
  for (int K = 1; K < 4; K++)
    for (int J = 1; J < 4; J++)
      for (int I = 1; I < 4; I++) {
        const int n = mpm_mesh_node(&s->mesh, I, J, K), N[3] = {I, J, K};
        for (int d = 0; d < 3; d++) {
          double want = 0.0;
          for (int c = 0; c < 8; c++) {             /* the eight boxes around N */
            const int b[3] = {I - 1 + (c & 1), J - 1 + (c >> 1 & 1), K - 1 + (c >> 2 & 1)};
            want += (b[d] == N[d] ? A : -A) * box_stress_of(b[0] + 4 * (b[1] + 4 * b[2]));
          }
          ck_assert_double_eq_tol(s->nm[n] * mpm_sim_node(s, n)[3 + d], want, 1e-11);
          fmax_ = fmax(fmax_, fabs(want));
        }
      }
  ck_assert_double_ge(fmax_, 0.01);          /* forces of 1e-2 N and more */
  mpm_sim_free(s);
}
END_TEST

/* A filled box's volume rate is the mean divergence of the trilinear grid
 * velocity over it, phi (1 / V_e) sum_i v_i . int_e grad N_i dV: a block
 * of 4 x 4 x 4 boxes inside a larger free mesh, moving with v = D x, its
 * eight inner boxes filled (phi = 1; the nodes of a regular block carry the
 * exact field), so their points' volumes grow by exp(dt tr D); the boxes
 * along the block's faces are not filled. */
START_TEST(t_element_divergence)
{
  static const double D[3][3] = {{1.0, 0.5, 0.0}, {-0.25, -0.5, 0.75}, {0.0, 0.3, 2.0}};
  mpm_config c;
  sim_config_box(&c, "delta", 6, 6, 6);
  c.bc.left = c.bc.right = c.bc.bottom = c.bc.top = MPM_BC_FREE;
  c.bc.front = c.bc.back = MPM_BC_FREE;
  c.fill[0].xmin = c.fill[0].ymin = c.fill[0].zmin = 0.01;
  c.fill[0].xmax = c.fill[0].ymax = c.fill[0].zmax = 0.05;
  c.time.dt = 1e-5;
  c.mesh.dilatation = MPM_DILATATION_ELEMENT;
  mpm_sim *s = make(&c);
  mpm_points *P = s->pts;
  double *v0 = malloc(P->n * sizeof *v0);
  for (size_t p = 0; p < P->n; p++) {
    const double x[3] = {P->x[p], P->y[p], P->z[p]};
    double *const v[3] = {&P->vx[p], &P->vy[p], &P->vz[p]};
    for (int i = 0; i < 3; i++)
      *v[i] = D[i][0] * x[0] + D[i][1] * x[1] + D[i][2] * x[2];
    v0[P->id[p]] = P->vol[p];
  }
  int inner = 0;
  double worst = 0.0;
  for (size_t p = 0; p < P->n; p++)           /* the points of the inner boxes, 2 <= i, j, k <= 3 */
    inner += fabs(P->x[p] - 0.03) < 0.01 && fabs(P->y[p] - 0.03) < 0.01 && fabs(P->z[p] - 0.03) < 0.01;
  steps(s, 1);
  const double want = exp(1e-5 * (D[0][0] + D[1][1] + D[2][2]));
  for (size_t p = 0; p < P->n; p++) {
    const double x = P->x[p], y = P->y[p], z = P->z[p];
    if (fabs(x - 0.03) < 0.01 && fabs(y - 0.03) < 0.01 && fabs(z - 0.03) < 0.01)
      worst = fmax(worst, fabs(P->vol[p] / v0[P->id[p]] - want));
  }
  ck_assert_int_eq(inner, 64);
  ck_assert_double_le(worst, 1e-13);          /* a rate of 2.5 /s over 1e-5 s: 2.5e-5 */
  int filled = 0;                             /* the eight inner boxes, no other */
  for (int e = 0; e < 216; e++)
    if (s->uel[7 * e] > 0.0) {
      const int i = e % 6, j = e / 6 % 6, k = e / 36;
      ck_assert(i >= 2 && i <= 3 && j >= 2 && j <= 3 && k >= 2 && k <= 3);
      ck_assert_double_eq_tol(s->uel[7 * e], 1.0, 1e-4);   /* phi: the volumes after the step */
      filled++;
    }
  ck_assert_int_eq(filled, 8);
  free(v0);
  mpm_sim_free(s);
}
END_TEST

static double linear_sm3(double x, double y, double z)
{
  return -(1000.0 + 20000.0 * x + 30000.0 * y - 10000.0 * z);
}

/* The projection of "element" gives each filled box's dense points a
 * limited linear field about their centroid: a linear mean stress comes
 * back exactly (the slopes of its box means are exact, also beside the
 * walls), where "unit" sets it to each box's mean (a quarter box off at
 * the points); a field that is not linear keeps its box means. */
START_TEST(t_element_linear)
{
  for (int rule = 0; rule < 2; rule++) {
    mpm_sim *s = element_box(rule ? MPM_DILATATION_UNIT : MPM_DILATATION_ELEMENT, 1, 1e-10);
    const mpm_points *P = s->pts;
    for (size_t p = 0; p < P->n; p++)
      set_isotropic3(s, p, linear_sm3(P->x[p], P->y[p], P->z[p]));
    steps(s, 1);
    double worst = 0.0;
    for (size_t p = 0; p < P->n; p++) {
      const double sm = (P->sxx[p] + P->syy[p] + P->szz[p]) / 3.0;
      worst = fmax(worst, fabs(sm - linear_sm3(P->x[p], P->y[p], P->z[p])));
    }
    if (rule == 0)
      ck_assert_double_le(worst, 1e-9 * 2400.0);
    else
      ck_assert_double_ge(worst, 0.25 * 0.01 * 30000.0);
    mpm_sim_free(s);
  }
  mpm_sim *s = element_box(MPM_DILATATION_ELEMENT, 0, 1e-10);
  const mpm_points *P = s->pts;
  for (size_t p = 0; p < P->n; p++) {
    const double x = P->x[p], y = P->y[p], z = P->z[p];
    set_isotropic3(s, p, linear_sm3(x, y, z) + 500.0 * sin(4000.0 * x * y + 900.0 * z));
  }
  double v[2][64], sv[2][64];
  for (int k = 0; k < 2; k++) {
    for (int e = 0; e < 64; e++)
      v[k][e] = sv[k][e] = 0.0;
    for (size_t p = 0; p < P->n; p++) {
      const double x[3] = {P->x[p], P->y[p], P->z[p]};
      int u[3];
      double l[3];
      ck_assert_int_eq(mpm_mesh_locate(&s->mesh, x, u, l), 0);
      const int e = u[0] + 4 * (u[1] + 4 * u[2]);
      v[k][e] += P->vol[p];
      sv[k][e] += P->vol[p] * (P->sxx[p] + P->syy[p] + P->szz[p]) / 3.0;
    }
    if (k == 0)
      steps(s, 1);
  }
  double spread = 0.0;
  for (int e = 0; e < 64; e++) {
    ck_assert_double_eq_tol(sv[1][e] / v[1][e], sv[0][e] / v[0][e], 1e-9 * 3000.0);
    spread = fmax(spread, fabs(sv[0][e] / v[0][e] - sv[0][0] / v[0][0]));
  }
  ck_assert_double_ge(spread, 100.0);
  mpm_sim_free(s);
}
END_TEST

/* APIC ([JSS+15]) carries an affine velocity field v = v0 + A x exactly:
 * with C_p = A the nodes receive (mv)_i = sum S m_p (v_p + A (x_i - x_p))
 * = m_i (v0 + A x_i) (every shape reproduces linear functions), so a
 * stress-free box without gravity or walls leaves the step with
 * v_p = v0 + A x_p (the positions of the start) and C_p = A at every
 * point, also at its faces; PIC loses the rotation there. Momentum is kept
 * (sum S (x_i - x_p) = 0). Returns the largest error of v_p and C_p. */
static double apic_step3(const char *shape, int apic)
{
  static const double v0[3] = {0.3, -0.2, 0.1};
  static const double A[3][3] = {{0.5, -2.0, 0.75}, {1.5, -0.25, -1.0}, {-0.5, 1.25, 0.2}};
  mpm_config c;
  sim_config_box(&c, shape, 5, 5, 5);
  c.bc.left = c.bc.right = c.bc.bottom = c.bc.top = MPM_BC_FREE;
  c.bc.front = c.bc.back = MPM_BC_FREE;
  c.fill[0].xmin = c.fill[0].ymin = c.fill[0].zmin = 0.01;
  c.fill[0].xmax = c.fill[0].ymax = c.fill[0].zmax = 0.04;
  c.time.transfer = apic ? MPM_TRANSFER_APIC : MPM_TRANSFER_FLIP;
  c.time.flip = 0.0;                              /* PIC: the point takes sum S v_i */
  mpm_sim *s = make(&c);
  mpm_points *P = s->pts;
  const size_t n = P->n;
  ck_assert_uint_eq(n, 216);
  double (*x)[3] = malloc(n * sizeof *x), q0[3] = {0.0, 0.0, 0.0}, m = 0.0;
  double *const v[3] = {P->vx, P->vy, P->vz};
  double *const C[9] = {P->cxx, P->cxy, P->cxz, P->cyx, P->cyy, P->cyz, P->czx, P->czy, P->czz};
  for (size_t p = 0; p < n; p++) {
    x[p][0] = P->x[p];
    x[p][1] = P->y[p];
    x[p][2] = P->z[p];
    for (int i = 0; i < 3; i++) {
      v[i][p] = v0[i] + A[i][0] * x[p][0] + A[i][1] * x[p][1] + A[i][2] * x[p][2];
      for (int j = 0; j < 3; j++)
        C[3 * i + j][p] = A[i][j];
      q0[i] += P->mass[p] * v[i][p];
    }
    m += P->mass[p];
  }
  steps(s, 1);
  double worst = 0.0, q1[3] = {0.0, 0.0, 0.0};
  for (size_t p = 0; p < n; p++) {
    const int k = P->id[p];                      /* the store may be reordered */
    for (int i = 0; i < 3; i++) {
      const double want = v0[i] + A[i][0] * x[k][0] + A[i][1] * x[k][1] + A[i][2] * x[k][2];
      worst = fmax(worst, fabs(v[i][p] - want));
      for (int j = 0; apic && j < 3; j++)
        worst = fmax(worst, fabs(C[3 * i + j][p] - A[i][j]));
      q1[i] += P->mass[p] * v[i][p];
    }
  }
  for (int i = 0; i < 3; i++)                    /* |v| < 4 m/s: 1e-12 is round-off */
    ck_assert_msg(fabs(q1[i] - q0[i]) <= 1e-12 * m, "%s: momentum %d changed by %g", shape, i,
                  q1[i] - q0[i]);
  free(x);
  mpm_sim_free(s);
  return worst;
}

START_TEST(t_apic_affine)
{
  const double e = apic_step3(shapes[_i], 1);
  ck_assert_msg(e <= 1e-12, "%s: APIC off the affine field by %g", shapes[_i], e);
  ck_assert_double_ge(apic_step3(shapes[_i], 0), 1e-3);   /* PIC */
}
END_TEST

/* Across the periodic faces: a box filling a periodic 4 x 4 x 4 mesh with
 * a velocity periodic along every axis and C_p its gradient, one step;
 * then everything shifted by one unit along x, y and z (positions
 * wrapped). The points that straddle the seams are others after the shift,
 * so an offset x_i - x_p taken from a wrong image, or a node's position
 * decoded wrongly from its storage index, shows. v[3 id + d]: the result. */
static void apic_periodic_step3(const char *shape, int shift, double *v)
{
  mpm_config c;
  sim_config_box(&c, shape, 4, 4, 4);
  c.time.transfer = MPM_TRANSFER_APIC;
  mpm_sim *s = make(&c);
  mpm_points *P = s->pts;
  const double k = 8.0 * atan(1.0) / 0.04, len = 0.04;   /* 2 pi / period */
  for (size_t p = 0; p < P->n; p++) {
    const double x = P->x[p], y = P->y[p], z = P->z[p];    /* the field before the shift */
    P->vx[p] = 0.3 + 0.2 * sin(k * y) + 0.1 * cos(k * z);
    P->vy[p] = -0.2 + 0.1 * cos(k * x) * sin(k * z);
    P->vz[p] = 0.05 * sin(k * (x + y));
    P->cxx[p] = 0.0;
    P->cxy[p] = 0.2 * k * cos(k * y);
    P->cxz[p] = -0.1 * k * sin(k * z);
    P->cyx[p] = -0.1 * k * sin(k * x) * sin(k * z);
    P->cyy[p] = 0.0;
    P->cyz[p] = 0.1 * k * cos(k * x) * cos(k * z);
    P->czx[p] = P->czy[p] = 0.05 * k * cos(k * (x + y));
    P->czz[p] = 0.0;
    P->x[p] = fmod(x + shift * 0.01, len);
    P->y[p] = fmod(y + shift * 0.01, len);
    P->z[p] = fmod(z + shift * 0.01, len);
  }
  steps(s, 1);
  ck_assert_uint_eq(P->n, 512);
  for (size_t p = 0; p < P->n; p++) {
    v[3 * P->id[p]] = P->vx[p];
    v[3 * P->id[p] + 1] = P->vy[p];
    v[3 * P->id[p] + 2] = P->vz[p];
  }
  mpm_sim_free(s);
}

START_TEST(t_apic_periodic)
{
  double *a = malloc(2 * 3 * 512 * sizeof *a), *b = a + 3 * 512;
  apic_periodic_step3(shapes[_i], 0, a);
  apic_periodic_step3(shapes[_i], 1, b);
  double worst = 0.0, spread = 0.0;
  for (int k = 0; k < 3 * 512; k++) {
    worst = fmax(worst, fabs(a[k] - b[k]));
    spread = fmax(spread, fabs(a[k] - a[k % 3]));
  }
  ck_assert_double_gt(spread, 0.05);               /* the field varies */
  ck_assert_msg(worst <= 1e-12, "%s: the shifted box differs by %g m/s", shapes[_i], worst);
  free(a);
}
END_TEST

/* The position of point p as a message writes it, "(x, y, z)". */
static void position3(const mpm_points *P, size_t p, char *buf, size_t len)
{
  snprintf(buf, len, "(%.6g, %.6g, %.6g)", P->x[p], P->y[p], P->z[p]);
}

/* The index of the point of id `id`, or P->n. */
static size_t point_of_id(const mpm_points *P, int id)
{
  size_t p = 0;
  while (p < P->n && P->id[p] != id)
    p++;
  return p;
}

/* A blow-up in 3D is named from the 3D fields (health.c).
 * Set by hand in a periodic elastic box (stable step): a non-finite shear
 * stress out of the plane (syz), a volume that is not positive (in m^3),
 * a non-finite z velocity: each is the point, the field, the value, the
 * position (x, y, z), the time, and, the step being stable, a material
 * parameter as the likely cause.
 * Driven by the step: (1) CPDI1 with an infinite third extent vector r3z:
 * the step's stencil meets it and the run stops naming it (not "left the
 * mesh"); (2) a box whose z units are a quarter of its x and y units, run
 * with dt three times its stable step, cfl (dz / c_p): the step is stable
 * for dx and dy (dt c_p = 0.75 dx), so only the third axis makes it
 * unstable; the run blows up within a few dozen steps, and the report
 * names a point that is in the store at the position it gives, the time
 * the run reached, and the time step as the cause, 3 times the stable
 * step; (3) the NGF explicit diffusion limit with dz: with dz a third of
 * dx, (dt/n_sub) A^2 d^2/t0 (2/dx^2 + 2/dy^2) is about 0.5 but with
 * + 2/dz^2 about 2.8 (t0 = 25 us), so a blow-up names the diffusion of g,
 * with the 2/dz^2 term. */
START_TEST(t_health)
{
  mpm_config c;
  sim_config_box(&c, "ugimp", 4, 4, 4);
  mpm_sim *s = make(&c);
  mpm_points *P = s->pts;
  mpm_err err = {0};
  char at[128], want[512];
  ck_assert_int_eq(mpm_sim_check_state(s, 0.5, &err), MPM_OK);
  P->syz[5] = NAN;
  ck_assert_int_eq(mpm_sim_check_state(s, 0.5, &err), MPM_ENONFINITE);
  position3(P, 5, at, sizeof at);
  snprintf(want, sizeof want, "point %d: stress syz = nan Pa at %s m, t = 0.5 s: the stress is "
           "not finite; likely cause: a material parameter", P->id[5], at);
  ck_assert_msg(strstr(err.msg, want) != NULL, "%s\nwant %s", err.msg, want);
  P->syz[5] = 0.0;
  const double v7 = P->vol[7];
  P->vol[7] = 0.0;
  ck_assert_int_eq(mpm_sim_check_state(s, 0.25, &err), MPM_ENONFINITE);
  position3(P, 7, at, sizeof at);
  snprintf(want, sizeof want, "point %d: volume = 0 m^3 at %s m, t = 0.25 s: the volume is not "
           "positive", P->id[7], at);
  ck_assert_msg(strstr(err.msg, want) != NULL, "%s\nwant %s", err.msg, want);
  P->vol[7] = v7;
  P->vz[9] = -INFINITY;
  ck_assert_int_eq(mpm_sim_check_state(s, 0.125, &err), MPM_ENONFINITE);
  ck_assert_msg(strstr(err.msg, "velocity vz = -inf m/s") != NULL, "%s", err.msg);
  mpm_sim_free(s);

  /* (1) CPDI1: an infinite r3z met by the step */
  sim_config_box(&c, "cpdi", 4, 4, 4);
  s = make(&c);
  P = s->pts;
  P->r3z[3] = INFINITY;
  ck_assert_int_eq(mpm_sim_step(s, &err), MPM_ENONFINITE);
  position3(P, 3, at, sizeof at);
  snprintf(want, sizeof want, "point %d: extent r3z = inf m at %s m, t = 0 s: the extent is not "
           "finite; likely cause: a material parameter", P->id[3], at);
  ck_assert_msg(strstr(err.msg, want) && !strstr(err.msg, "left the mesh"), "%s\nwant %s",
                err.msg, want);
  mpm_sim_free(s);

  /* (2) unstable along z alone */
  sim_config_box(&c, "ugimp", 4, 4, 8);
  c.mesh.dz = 0.0025;
  c.fill[0].zmax = 8 * 0.0025;
  c.time.dt_unstable_ok = 1;
  c.time.dt = 3.0 * mpm_sim_stable_dt(&c);
  s = make(&c);
  P = s->pts;
  unsigned st = 777u;
  for (size_t p = 0; p < P->n; p++)
    P->vz[p] = 1e-3 * noise(&st);                /* a seed for the unstable modes */
  int rc = MPM_OK, n = 0;
  while (rc == MPM_OK && n < 500) {
    rc = mpm_sim_step(s, &err);
    n++;
  }
  printf("unstable along z: step %d: %s\n", n, err.msg);
  ck_assert_int_eq(rc, MPM_ENONFINITE);
  int id = -1;
  ck_assert_int_eq(sscanf(err.msg, "point %d:", &id), 1);
  const size_t p = point_of_id(P, id);
  ck_assert_uint_lt(p, P->n);
  position3(P, p, at, sizeof at);
  char tnow[256], tnext[256];
  snprintf(tnow, sizeof tnow, " at %s m, t = %.6g s: ", at, s->t);
  snprintf(tnext, sizeof tnext, " at %s m, t = %.6g s: ", at, s->t + s->dt);
  ck_assert_msg(strstr(err.msg, tnow) || strstr(err.msg, tnext), "%s\nwant the position %s "
                "and the time %.6g s", err.msg, at, s->t);
  ck_assert_msg(strstr(err.msg, ": speed ") || strstr(err.msg, " = "), "%s", err.msg);
  ck_assert_msg(!strstr(err.msg, "a runaway") || strstr(err.msg, "(min(dx, dy, dz) / dt = "),
                "%s", err.msg);               /* the limit of a runaway is dz's here */
  snprintf(want, sizeof want, "likely cause: the time step: dt = %.3g s is 3 times the stable "
           "step %.3g s", s->dt, mpm_sim_stable_dt(&c));
  ck_assert_msg(strstr(err.msg, want) != NULL, "%s\nwant %s", err.msg, want);
  mpm_sim_free(s);

  /* (3) the NGF diffusion limit with dz */
  sim_config_box(&c, "ugimp", 4, 4, 6);
  sim_config_material(&c, "ngf_hyper", 1e6);
  c.material.A = 0.48;
  c.material.t0 = 2.5e-5;
  c.material.n_sub = 1;
  c.mesh.dz = 0.01 / 3.0;
  c.fill[0].zmax = 6 * c.mesh.dz;
  s = make(&c);
  const double r2 = mpm_material_ngf_diffusion_number(&s->par, s->dt, 1, 0.01, 0.01, 0.0);
  const double r3 = mpm_material_ngf_diffusion_number(&s->par, s->dt, 1, 0.01, 0.01, c.mesh.dz);
  ck_assert_msg(r2 < 0.6 && r3 > 2.0, "diffusion numbers %g, %g", r2, r3);
  s->pts->sxx[2] = NAN;
  ck_assert_int_eq(mpm_sim_check_state(s, 0.5, &err), MPM_ENONFINITE);
  ck_assert_msg(strstr(err.msg, "likely cause: the diffusion of g: ") &&
                strstr(err.msg, "2/dx^2 + 2/dy^2 + 2/dz^2") &&
                strstr(err.msg, "(key 'material.n_sub')"), "%s", err.msg);
  mpm_sim_free(s);
}
END_TEST

int main(void)
{
  Suite *su = suite_create("solver_box");
  TCase *tc = tcase_create("step");
  tcase_set_timeout(tc, 120);
  tcase_add_loop_test(tc, t_free_flight, 0, 6);
  tcase_add_loop_test(tc, t_free_fall, 0, 6);
  tcase_add_loop_test(tc, t_momentum, 0, 6);
  tcase_add_loop_test(tc, t_plane, 0, 6);
  tcase_add_loop_test(tc, t_plane_ramp, 0, 4);
  tcase_add_loop_test(tc, t_apic_affine, 0, 3);
  tcase_add_loop_test(tc, t_apic_periodic, 0, 3);
  tcase_add_loop_test(tc, t_outlet, 0, 5);
  tcase_add_test(tc, t_stop_mass);
  tcase_add_loop_test(tc, t_hyper_state_density, 0, 2);
  tcase_add_loop_test(tc, t_lithostatic, 0, 2);
  tcase_add_loop_test(tc, t_absorb_layer, 0, 3);
  tcase_add_test(tc, t_unit_options);
  tcase_add_test(tc, t_element_uniform);
  tcase_add_test(tc, t_element_forces);
  tcase_add_test(tc, t_element_divergence);
  tcase_add_test(tc, t_element_linear);
  tcase_add_test(tc, t_health);
  suite_add_tcase(su, tc);
  SRunner *sr = srunner_create(su);
  srunner_run_all(sr, CK_NORMAL);
  const int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf ? EXIT_FAILURE : EXIT_SUCCESS;
}
