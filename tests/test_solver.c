/* test_solver.c: the run driver and the grid update, on cases small enough to
 * work out by hand.
 *
 *  - A stress-free point in the unit of a mesh corner whose left and bottom
 *    edges are no-slip walls: three of its four Q4 nodes are held, so after
 *    one step the grid velocity it sees is S_free v = v/4, and its FLIP
 *    velocity must drop to that too (the wall's velocity jump enters a_i).
 *    With a_i = f_i / m_i = 0 on the held nodes it would keep v.
 *  - stop.ke: material at rest stops at t_min; moving material runs to t_end. */
#include <check.h>
#include <math.h>
#include <string.h>

#include "core/config.h"
#include "diag/diag.h"
#include "solver/solver.h"

/* One unit of size h, walls as given, one fill of the whole unit with
 * ppu x ppu points of stress-free elastic material at velocity (vx, vy). */
static void base_config(mpm_config *c, int nx, int ppu, double vx, double vy)
{
  memset(c, 0, sizeof *c);
  c->mesh.nx = nx;
  c->mesh.ny = nx;
  c->mesh.dx = c->mesh.dy = 0.1;
  strcpy(c->mesh.topology, "q4");
  strcpy(c->mesh.diagonal, "/");
  strcpy(c->mesh.shape, "delta");
  c->time.dt = 1e-4;
  c->time.cfl = 0.5;
  c->time.t_end = 1e-2;
  c->time.frame_dt = 1e-2;
  c->time.flip = 1.0;
  strcpy(c->material.model, "elastic");
  c->material.E = 1e6;
  c->material.nu = 0.3;
  c->material.rho_s = 2450;
  c->material.rho_c = 1500;
  c->material.mu_s = 0.3819;
  c->material.mu_2 = 0.6435;
  c->material.I0 = 0.279;
  c->material.d = 0.005;
  c->material.t0 = 1e-3;
  c->bc.left = c->bc.bottom = MPM_BC_NOSLIP;
  c->bc.right = c->bc.top = MPM_BC_FREE;
  c->nfill = 1;
  mpm_fill_config *f = &c->fill[0];
  f->shape = MPM_FILL_RECTANGLE;
  f->xmax = f->ymax = 0.1;
  f->ppu = ppu;
  f->density = 1500;
  f->vx = vx;
  f->vy = vy;
  strcpy(f->name, "block");
}

START_TEST(t_wall_stops_flip_velocity)
{
  mpm_config c;
  base_config(&c, 1, 1, 1.0, 0.0);  /* one point at the unit centre, moving along the floor */
  mpm_sim *s = NULL;
  mpm_err err = {0};
  ck_assert_int_eq(mpm_sim_create(&s, &c, &err), MPM_OK);
  ck_assert_uint_eq(s->pts->n, 1);
  const double x0 = s->pts->x[0], dt = s->dt;
  ck_assert_int_eq(mpm_sim_step(s, &err), MPM_OK);
  /* nodes (0,0), (1,0), (0,1) held; node (1,1) keeps v = 1 (no force: no stress);
   * S = 1/4 each at the centre */
  ck_assert_double_eq_tol(s->pts->vx[0], 0.25, 1e-14);
  ck_assert_double_eq_tol(s->pts->vy[0], 0.0, 1e-14);
  ck_assert_double_eq_tol(s->pts->x[0] - x0, 0.25 * dt, 1e-14);
  mpm_sim_free(s);
}
END_TEST

/* PIC (flip = 0): a point's new velocity is the grid velocity it moved with,
 * v_p = sum S v_i = (x_{n+1} - x_n) / dt, whatever velocities the points
 * brought; pure FLIP keeps the part the grid does not see, so there the
 * two differ for this non-uniform start. */
START_TEST(t_pic_velocity_is_displacement_rate)
{
  for (int pic = 1; pic >= 0; pic--) {
    mpm_config c;
    base_config(&c, 3, 2, 0.0, 0.0);
    c.bc.left = c.bc.bottom = MPM_BC_FREE;
    c.fill[0].xmin = c.fill[0].ymin = 0.1;
    c.fill[0].xmax = c.fill[0].ymax = 0.2;
    c.time.flip = pic ? 0.0 : 1.0;
    mpm_sim *s = NULL;
    mpm_err err = {0};
    ck_assert_int_eq(mpm_sim_create(&s, &c, &err), MPM_OK);
    ck_assert_uint_eq(s->pts->n, 4);
    double x0[4], y0[4], worst = 0.0;
    for (int p = 0; p < 4; p++) {        /* a non-uniform velocity field */
      s->pts->vx[p] = (p & 1) ? 1.0 : -0.5;
      s->pts->vy[p] = (p & 2) ? 0.25 : 0.75;
      x0[p] = s->pts->x[p];
      y0[p] = s->pts->y[p];
    }
    ck_assert_int_eq(mpm_sim_step(s, &err), MPM_OK);
    for (int p = 0; p < 4; p++) {
      double ex = s->pts->vx[p] - (s->pts->x[p] - x0[p]) / s->dt;
      double ey = s->pts->vy[p] - (s->pts->y[p] - y0[p]) / s->dt;
      worst = fmax(worst, fmax(fabs(ex), fabs(ey)));
    }
    if (pic)
      ck_assert_double_le(worst, 1e-9);   /* x is O(0.1), dt 1e-4: round-off ~1e-12 / 1e-4 */
    else
      ck_assert_double_ge(worst, 0.1);
    mpm_sim_free(s);
  }
}
END_TEST

/* A block at rest with no gravity: the kinetic energy is 0 < stop.ke from
 * the start, so the run ends at the first step at or after t_min. */
START_TEST(t_stop_at_rest)
{
  mpm_config c;
  base_config(&c, 4, 2, 0.0, 0.0);
  c.stop.ke = 1e-10;
  c.stop.t_min = 2.5e-3;
  mpm_sim *s = NULL;
  mpm_err err = {0};
  ck_assert_int_eq(mpm_sim_create(&s, &c, &err), MPM_OK);
  ck_assert_int_eq(mpm_sim_run(s, NULL, NULL, NULL, &err), MPM_OK);
  ck_assert_int_eq(s->stop, MPM_STOP_KE);
  ck_assert_double_eq_tol(s->t, 2.5e-3, 1e-12);   /* 25 steps of 1e-4 s */
  ck_assert_double_eq(s->stop_value, 0.0);
  mpm_sim_free(s);
}
END_TEST

/* Moving material (1 m/s, no walls in its way for 1e-2 s) never falls below
 * the threshold: the run reaches t_end. */
START_TEST(t_stop_runs_to_end)
{
  mpm_config c;
  base_config(&c, 4, 2, 1.0, 0.0);
  c.bc.left = c.bc.bottom = MPM_BC_FREE;
  c.fill[0].xmin = c.fill[0].ymin = 0.1;
  c.fill[0].xmax = c.fill[0].ymax = 0.2;
  c.stop.ke = 0.4;                                  /* below 1/2 v^2 = 0.5 J/kg */
  mpm_sim *s = NULL;
  mpm_err err = {0};
  ck_assert_int_eq(mpm_sim_create(&s, &c, &err), MPM_OK);
  ck_assert_int_eq(mpm_sim_run(s, NULL, NULL, NULL, &err), MPM_OK);
  ck_assert_int_eq(s->stop, MPM_STOP_T_END);
  ck_assert_double_eq_tol(s->t, 1e-2, 1e-12);
  ck_assert_double_eq_tol(mpm_diag_kinetic_per_mass(s->pts), 0.5, 1e-12);
  mpm_sim_free(s);
}
END_TEST

int main(void)
{
  Suite *su = suite_create("solver");
  TCase *tc = tcase_create("solver");
  tcase_add_test(tc, t_wall_stops_flip_velocity);
  tcase_add_test(tc, t_pic_velocity_is_displacement_rate);
  tcase_add_test(tc, t_stop_at_rest);
  tcase_add_test(tc, t_stop_runs_to_end);
  suite_add_tcase(su, tc);
  SRunner *sr = srunner_create(su);
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf == 0 ? 0 : 1;
}
