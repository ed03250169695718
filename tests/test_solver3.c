/* test_solver3.c: the 3D step (mesh.nz > 0) from its equations.
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
 *  - threads: a 3D column collapsing onto a rough floor against walls is
 *    bitwise the same on one and on two threads (bands of unit layers). */
#include <check.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/config.h"
#include "solver/solver.h"
#include "sim_config.h"

/* An elastic box of nx x ny x nz units of 1 cm filled with 2 x 2 x 2 points
 * a unit; faces periodic unless set otherwise by the caller. */
static void box_config(mpm_config *c, const char *shape, int nx, int ny, int nz)
{
  sim_config_clear(c);
  c->mesh.nx = nx;
  c->mesh.ny = ny;
  c->mesh.nz = nz;
  c->mesh.dx = c->mesh.dy = c->mesh.dz = 0.01;
  strcpy(c->mesh.topology, "q4");
  strcpy(c->mesh.diagonal, "/");
  strcpy(c->mesh.shape, shape);
  c->time.cfl = 0.5;
  c->time.t_end = 1.0;
  c->time.frame_dt = 1.0;
  c->time.flip = 1.0;
  sim_config_material(c, "elastic", 1e6);
  c->bc.left = c->bc.right = c->bc.bottom = c->bc.top = MPM_BC_PERIODIC;
  c->bc.front = c->bc.back = MPM_BC_PERIODIC;
  c->nfill = 1;
  mpm_fill_config *f = &c->fill[0];
  f->shape = MPM_FILL_RECTANGLE;
  f->xmax = 0.01 * nx;
  f->ymax = 0.01 * ny;
  f->zmax = 0.01 * nz;
  f->ppu = 2;
  f->density = 1500;
  strcpy(f->name, "box");
}

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

START_TEST(t_free_flight)
{
  mpm_config c;
  box_config(&c, shapes[_i], 3, 3, 3);
  c.fill[0].vx = 0.3;
  c.fill[0].vy = -0.2;
  c.fill[0].vz = 0.1;
  mpm_sim *s = make(&c);
  const mpm_points *P = s->pts;
  ck_assert_int_eq((int)P->n, 216);
  double *x0 = malloc(3 * P->n * sizeof *x0);
  for (size_t p = 0; p < P->n; p++) {
    x0[3 * p] = P->x[p];
    x0[3 * p + 1] = P->y[p];
    x0[3 * p + 2] = P->z[p];
  }
  steps(s, 20);
  const double t = s->t, v[3] = {0.3, -0.2, 0.1}, len = 0.03;
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
  box_config(&c, shapes[_i], 4, 8, 4);
  c.bc.left = c.bc.right = c.bc.bottom = c.bc.top = MPM_BC_FREE;
  c.bc.front = c.bc.back = MPM_BC_FREE;
  c.fill[0].xmin = c.fill[0].ymin = c.fill[0].zmin = 0.01;
  c.fill[0].xmax = c.fill[0].zmax = 0.03;
  c.fill[0].ymax = 0.07;
  c.gravity.gx = 1.0;
  c.gravity.gy = -9.8;
  c.gravity.gz = 0.5;
  mpm_sim *s = make(&c);
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
  box_config(&c, shapes[_i], 4, 4, 4);
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

/* A column collapsing onto a rough floor between a symmetry plane and a
 * frictionless wall, periodic in z; nz = 0 is its plane counterpart. */
static void column_config(mpm_config *c, const char *shape, int nz, const char *model)
{
  box_config(c, shape, 12, 8, nz);
  sim_config_material(c, model, 1e6);
  c->bc.left = MPM_BC_SYMMETRY;
  c->bc.right = MPM_BC_FRICTIONLESS;
  c->bc.bottom = MPM_BC_NOSLIP;
  c->bc.top = MPM_BC_FREE;
  if (nz == 0)
    c->bc.front = c->bc.back = MPM_BC_FREE;
  c->gravity.gy = -9.8;
  c->fill[0].xmax = 0.05;
  c->fill[0].ymax = 0.06;
}

START_TEST(t_plane)
{
  mpm_config c2, c3;
  column_config(&c2, shapes[_i], 0, "mu_i");
  column_config(&c3, shapes[_i], 2, "mu_i");
  mpm_sim *s2 = make(&c2), *s3 = make(&c3);
  ck_assert_double_eq(s2->dt, s3->dt);
  steps(s2, 200);
  steps(s3, 200);
  const mpm_points *P = s2->pts, *Q = s3->pts;
  ck_assert_uint_eq(Q->n, 4 * P->n);            /* 2 x 2 points a unit along z, 2 units */
  double vmax = 0.0, dev = 0.0, wz = 0.0, pmax = 0.0, dp = 0.0;
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
    dev = fmax(dev, fabs(P->vx[best] - Q->vx[q]) + fabs(P->vy[best] - Q->vy[q]));
    wz = fmax(wz, fabs(Q->vz[q]));
    pmax = fmax(pmax, fabs(P->syy[best]));
    dp = fmax(dp, fabs(P->syy[best] - Q->syy[q]) + fabs(P->szz[best] - Q->szz[q]));
    ck_assert_int_eq(P->state[best], Q->state[q]);
    ck_assert_double_le(dbest, 1e-12);
  }
  ck_assert_double_gt(vmax, 0.01);             /* it flows */
  ck_assert_double_le(dev, 1e-9 * vmax);        /* round-off of 200 steps, not a scheme's */
  ck_assert_double_le(wz, 1e-12 * vmax);
  ck_assert_double_le(dp, 1e-9 * pmax);
  mpm_sim_free(s2);
  mpm_sim_free(s3);
}
END_TEST

/* A box draining through a square orifice in its floor (a disc with
 * _i = 1): points leave only through it, and the mass in the box plus the
 * mass removed stays the initial mass. */
START_TEST(t_outlet)
{
  mpm_config c;
  box_config(&c, "ugimp", 6, 6, 6);
  sim_config_material(&c, "mu_i", 1e6);
  c.bc.left = c.bc.right = c.bc.bottom = c.bc.front = c.bc.back = MPM_BC_NOSLIP;
  c.bc.top = MPM_BC_FREE;
  c.gravity.gy = -9.8;
  c.fill[0].ymax = 0.04;
  c.outlet.edge = MPM_OUTLET_BOTTOM;
  c.outlet.closed = MPM_BC_NOSLIP;
  c.outlet.from = c.outlet.from2 = 0.02;
  c.outlet.to = c.outlet.to2 = 0.04;
  c.outlet.shape = _i ? MPM_OUTLET_DISC : MPM_OUTLET_RECTANGLE;
  mpm_sim *s = make(&c);
  const double m0 = s->mass0;
  steps(s, 300);
  const mpm_points *P = s->pts;
  ck_assert_int_gt(s->nremoved, 10);
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

/* The unit options (material.state_density = "unit", mesh.dilatation =
 * "unit": B-bar with one mean stress per box): a settling column keeps its
 * momentum balance (the modified stress is still an internal force: the box
 * falls with g while nothing touches the floor) and after every step the
 * dense points of a box share one mean stress (sxx + syy + szz)/3. */
START_TEST(t_unit_options)
{
  mpm_config c;
  column_config(&c, "ugimp", 2, "mu_i");
  c.material.state_density = MPM_DENSITY_UNIT;
  c.mesh.dilatation = MPM_DILATATION_UNIT;
  mpm_sim *s = make(&c);
  const mpm_points *P = s->pts;
  const mpm_mesh3 *m = &s->mesh3;
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
      ck_assert_int_eq(mpm_mesh3_locate(m, x, u, l), 0);
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

#ifdef _OPENMP
START_TEST(t_threads)
{
  mpm_config c;
  column_config(&c, shapes[_i], 3, "mu_i");
  double *f[2];
  size_t n = 0;
  for (int k = 0; k < 2; k++) {
    omp_set_num_threads(k + 1);
    mpm_sim *s = make(&c);
    steps(s, 100);
    const mpm_points *P = s->pts;
    n = P->n;
    f[k] = malloc(12 * n * sizeof(double));
    const double *src[12] = {P->x, P->y, P->z, P->vx, P->vy, P->vz,
                             P->sxx, P->syy, P->szz, P->sxy, P->syz, P->szx};
    for (int a = 0; a < 12; a++)
      memcpy(f[k] + a * n, src[a], n * sizeof(double));
    mpm_sim_free(s);
  }
  ck_assert_int_eq(memcmp(f[0], f[1], 12 * n * sizeof(double)), 0);
  free(f[0]);
  free(f[1]);
}
END_TEST
#endif

int main(void)
{
  Suite *su = suite_create("solver3");
  TCase *tc = tcase_create("step");
  tcase_set_timeout(tc, 120);
  tcase_add_loop_test(tc, t_free_flight, 0, 3);
  tcase_add_loop_test(tc, t_free_fall, 0, 3);
  tcase_add_loop_test(tc, t_momentum, 0, 3);
  tcase_add_loop_test(tc, t_plane, 0, 3);
  tcase_add_loop_test(tc, t_outlet, 0, 2);
  tcase_add_test(tc, t_unit_options);
#ifdef _OPENMP
  tcase_add_loop_test(tc, t_threads, 0, 3);
#endif
  suite_add_tcase(su, tc);
  SRunner *sr = srunner_create(su);
  srunner_run_all(sr, CK_NORMAL);
  const int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf ? EXIT_FAILURE : EXIT_SUCCESS;
}
