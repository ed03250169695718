/* test_threads.c: a run does not depend on the number of OpenMP threads.
 *
 * A small column of mu(I) material collapses against a symmetry line onto a
 * rough floor (walls, flow, disconnection and uGIMP stencils spanning unit
 * boundaries all take part; and the same with delta weights, evaluated from
 * the located points). After the same number of steps with one thread and
 * with two or three, every point field must be bitwise equal: point-to-grid
 * sums each node band by band and in point order within a band, whatever
 * the thread that takes a band (solver/transfer.c), the bands come from a
 * stable sort, the point store is reordered the same way, and everything
 * else is per point. The same column of NGF material, seeded after 10 t0,
 * checks the unit sums of g and p (bands of unit rows again): split between
 * units by the point extents (material.g_average = "extent", two colours of
 * bands), and by their centres with the unit sampling of p^-1/2 and the
 * implicit diffusion. The element and hybrid densities of the state
 * decision sum their unit masses in point order on one thread; so do the
 * per-unit dilatations (the element rule on q4, the unit rule on
 * triangles), whose per-point and per-unit loops run in parallel.
 * On boxes (mesh.nz > 0) the same: a column collapsing onto a rough floor
 * against walls, periodic in z, is bitwise the same on one and on two
 * threads (bands of unit layers along z), with every shape, under FLIP and
 * under APIC with the per-unit rules.
 * Rigid bodies (a turning disc with friction, a free plate) in both
 * dimensions: the point fields and every step's forces and torques on them
 * bitwise the same on one and on two threads (the node rows' sums taken in
 * row order).
 * Every comparison first makes sure the threads were there: a parallel
 * region right before the run counts the threads that ran it (dynamic
 * adjustment off), and a comparison needs two or more. When the runtime
 * gives one thread only (OMP_THREAD_LIMIT=1, or no OpenMP), the program
 * says so and is skipped (exit 77), having compared nothing. */
#define _POSIX_C_SOURCE 200809L /* fork, waitpid */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/config.h"
#include "solver/solver.h"
#include "sim_config.h"

/* ngf: 0 mu(I); 1 NGF, extent rule; 2 NGF, centre rule, unit p sampling,
 * implicit diffusion. delta: delta weights instead of uGIMP. */
static void column_config(mpm_config *c, const char *topology, int ngf, int density, int delta)
{
  sim_config_clear(c);
  c->mesh.nx = 24;
  c->mesh.ny = 12;
  c->mesh.dx = c->mesh.dy = 0.01;
  strcpy(c->mesh.topology, topology);
  strcpy(c->mesh.diagonal, "mirror");
  c->mesh.mirror_x = 0.05;
  strcpy(c->mesh.shape, "ugimp");
  c->time.cfl = 0.5;
  c->time.t_end = 1.0;
  c->time.frame_dt = 1.0;
  c->time.flip = 1.0;
  c->gravity.gy = -9.8;
  sim_config_material(c, ngf ? "ngf" : "mu_i", 1e6);
  if (ngf) {
    c->material.A = 0.48;
    c->material.t_seed = 10.0 * c->material.t0;      /* seeded after ~60 of the steps */
    c->material.n_sub = 1;
    c->material.g_average = ngf == 1 ? MPM_NONLOCAL_EXTENT : MPM_NONLOCAL_CENTRE;
    if (ngf == 2) {
      c->material.p_sample = MPM_NGF_P_UNIT;
      c->material.diffusion = MPM_DIFFUSION_IMPLICIT;
    }
  }
  if (delta)
    strcpy(c->mesh.shape, "delta");
  c->material.state_density = density;
  if (density == MPM_DENSITY_UNIT) {   /* with the defaults' dilatation and APIC */
    c->mesh.dilatation = strcmp(topology, "q4") == 0 ? MPM_DILATATION_ELEMENT
                                                     : MPM_DILATATION_UNIT;
    c->time.transfer = MPM_TRANSFER_APIC;
  }
  c->bc.left = MPM_BC_SYMMETRY;
  c->bc.bottom = MPM_BC_NOSLIP;
  c->bc.right = MPM_BC_FRICTIONLESS;
  c->bc.top = MPM_BC_FREE;
  c->nfill = 1;
  mpm_fill_config *f = &c->fill[0];
  f->shape = MPM_FILL_RECTANGLE;
  f->xmax = 0.10;                 /* 320 points: above the parallel thresholds */
  f->ymax = 0.08;
  f->ppu = 2;
  f->density = 1500;
  strcpy(f->name, "column");
}

/* Ask for n threads (dynamic adjustment off, so that a parallel region
 * gets them if the runtime can give them) and return how many ran a
 * parallel region: each member of the team marks its own slot. */
static int use_threads(int n)
{
  int team = 1;
#ifdef _OPENMP
  enum { MAXT = 256 };
  unsigned char ran[MAXT] = {0};
  omp_set_dynamic(0);
  omp_set_num_threads(n);
#pragma omp parallel
  {
    const int t = omp_get_thread_num();
    if (t < MAXT)
      ran[t] = 1;
  }
  team = 0;
  for (int t = 0; t < MAXT; t++)
    team += ran[t];
#else
  (void)n;
#endif
  return team;
}

/* use_threads(n) in a child process, for the decision before the tests:
 * Check forks every test from this process, and the OpenMP runtime's
 * threads do not survive a fork, so this process must not start them.
 * -1 if the child could not run. */
static int threads_apart(int n)
{
  const pid_t pid = fork();
  if (pid < 0)
    return -1;
  if (pid == 0)
    _exit(use_threads(n) & 0xff);
  int st = 0;
  if (waitpid(pid, &st, 0) != pid || !WIFEXITED(st))
    return -1;
  return WEXITSTATUS(st);
}

/* Two runs compared bitwise: a on one thread, b on `team` threads (those
 * that ran the parallel region before b's run, asked for `asked`). */
static void expect_same(const double *a, const double *b, size_t n, int asked, int team,
                        const char *what)
{
  ck_assert_msg(team >= 2, "%s: asked for %d threads, %d ran: nothing to compare", what, asked,
                team);
  if (team != asked)
    printf("%s: asked for %d threads, %d ran; compared 1 with %d\n", what, asked, team, team);
  ck_assert_msg(memcmp(a, b, n * sizeof *a) == 0, "%s: fields differ between 1 and %d threads",
                what, team);
}

/* The point fields after nsteps steps on nthreads threads, as one array;
 * *team: the threads that ran a parallel region just before. */
static double *run_fields(const char *topology, int ngf, int density, int delta, int nthreads,
                          int nsteps, size_t *len, int *team)
{
  *team = use_threads(nthreads);
  mpm_config c;
  column_config(&c, topology, ngf, density, delta);
  mpm_sim *s = NULL;
  mpm_err err = {0};
  ck_assert_int_eq(mpm_sim_create(&s, &c, &err), MPM_OK);
  for (int k = 0; k < nsteps; k++)
    ck_assert_msg(mpm_sim_step(s, &err) == MPM_OK, "step %d: %s", k, err.msg);
  const mpm_points *P = s->pts;
  double vmax = 0.0;
  for (size_t p = 0; p < P->n; p++)
    vmax = fmax(vmax, hypot(P->vx[p], P->vy[p]));
  ck_assert_msg(vmax > 0.05, "max speed %g m/s: the column should be collapsing", vmax);
  if (ngf) {
    double gmax = 0.0;
    for (size_t p = 0; p < P->n; p++)
      gmax = fmax(gmax, P->g[p]);
    ck_assert_msg(s->seeded && gmax > 0.0, "NGF: g should be seeded and non-zero (max %g)", gmax);
  }
  const double *f[] = {P->x, P->y, P->vx, P->vy, P->sxx, P->syy, P->szz, P->sxy,
                       P->vol, P->gdp, P->g};
  const size_t nf = sizeof f / sizeof f[0], n = P->n;
  double *out = malloc(nf * n * sizeof *out);
  ck_assert_ptr_nonnull(out);
  for (size_t k = 0; k < nf; k++)
    memcpy(out + k * n, f[k], n * sizeof *out);
  *len = nf * n;
  mpm_sim_free(s);
  return out;
}

static void same_on_1_2_and_3_threads(const char *topology, int ngf, int density, int delta)
{
  size_t na, nb, nc;
  int ta, tb, tc;
  /* 400 steps, about 0.07 s: the column is failing; the store is reordered 25 times */
  double *a = run_fields(topology, ngf, density, delta, 1, 400, &na, &ta);
  double *b = run_fields(topology, ngf, density, delta, 3, 400, &nb, &tb);
  double *c = run_fields(topology, ngf, density, delta, 2, 400, &nc, &tc);
  ck_assert_int_eq(ta, 1);
  ck_assert_uint_eq(na, nb);
  ck_assert_uint_eq(na, nc);
  expect_same(a, b, na, 3, tb, topology);
  expect_same(a, c, na, 2, tc, topology);
  free(a);
  free(b);
  free(c);
}

START_TEST(t_q4_thread_count) { same_on_1_2_and_3_threads("q4", 0, MPM_DENSITY_POINT, 0); }
END_TEST

START_TEST(t_t3_thread_count) { same_on_1_2_and_3_threads("t3", 0, MPM_DENSITY_POINT, 0); }
END_TEST

START_TEST(t_q4_delta_thread_count) { same_on_1_2_and_3_threads("q4", 0, MPM_DENSITY_POINT, 1); }
END_TEST

START_TEST(t_t3_delta_thread_count) { same_on_1_2_and_3_threads("t3", 0, MPM_DENSITY_POINT, 1); }
END_TEST

START_TEST(t_ngf_extent_thread_count) { same_on_1_2_and_3_threads("q4", 1, MPM_DENSITY_POINT, 0); }
END_TEST

START_TEST(t_ngf_centre_thread_count) { same_on_1_2_and_3_threads("t3", 2, MPM_DENSITY_POINT, 0); }
END_TEST

/* The element and hybrid densities, and that they do change the run (else
 * the comparison above would not exercise their unit sums). */
START_TEST(t_density_thread_count)
{
  same_on_1_2_and_3_threads("q4", 0, MPM_DENSITY_ELEMENT, 0);
  same_on_1_2_and_3_threads("q4", 0, MPM_DENSITY_HYBRID, 0);
  same_on_1_2_and_3_threads("q4", 0, MPM_DENSITY_UNIT, 0);
  size_t na, nb;
  int ta, tb;
  double *a = run_fields("q4", 0, MPM_DENSITY_POINT, 0, 1, 400, &na, &ta);
  double *b = run_fields("q4", 0, MPM_DENSITY_HYBRID, 0, 1, 400, &nb, &tb);
  ck_assert_uint_eq(na, nb);
  ck_assert_msg(memcmp(a, b, na * sizeof *a) != 0, "hybrid density leaves the run unchanged");
  free(a);
  free(b);
}
END_TEST

/* ---- boxes ------------------------------------------------------------------ */

static const char *const shapes[] = {"delta", "ugimp", "cpdi"};

/* The fields of the 3D column (sim_config_column, 4 units along z: 960
 * points, above the parallel thresholds) after 100 steps on nthreads
 * threads, for loop index i: shape i % 3, FLIP (i < 3) or APIC with the
 * defaults' per-unit rules (the element dilatation, the unit density). */
static double *run_box(int i, int nthreads, size_t *len, int *team)
{
  *team = use_threads(nthreads);
  mpm_config c;
  sim_config_column(&c, shapes[i % 3], 4, "mu_i");
  if (i >= 3) {
    c.time.transfer = MPM_TRANSFER_APIC;
    c.mesh.dilatation = MPM_DILATATION_ELEMENT;
    c.material.state_density = MPM_DENSITY_UNIT;
  }
  mpm_sim *s = NULL;
  mpm_err err = {0};
  ck_assert_msg(mpm_sim_create(&s, &c, &err) == MPM_OK, "%s", err.msg);
  ck_assert_int_eq(s->dim, 3);
  for (int k = 0; k < 100; k++)
    ck_assert_msg(mpm_sim_step(s, &err) == MPM_OK, "step %d: %s", k, err.msg);
  const mpm_points *P = s->pts;
  double vmax = 0.0;
  for (size_t p = 0; p < P->n; p++)
    vmax = fmax(vmax, hypot(hypot(P->vx[p], P->vy[p]), P->vz[p]));
  ck_assert_msg(vmax > 0.01, "max speed %g m/s: the column should be collapsing", vmax);
  const double *f[] = {P->x, P->y, P->z, P->vx, P->vy, P->vz,
                       P->sxx, P->syy, P->szz, P->sxy, P->syz, P->szx};
  const size_t nf = sizeof f / sizeof f[0], n = P->n;
  double *out = malloc(nf * n * sizeof *out);
  ck_assert_ptr_nonnull(out);
  for (size_t k = 0; k < nf; k++)
    memcpy(out + k * n, f[k], n * sizeof *out);
  *len = nf * n;
  mpm_sim_free(s);
  return out;
}

START_TEST(t_box_thread_count)
{
  size_t na, nb;
  int ta, tb;
  double *a = run_box(_i, 1, &na, &ta);
  double *b = run_box(_i, 2, &nb, &tb);
  ck_assert_int_eq(ta, 1);
  ck_assert_uint_eq(na, nb);
  char what[64];
  snprintf(what, sizeof what, "boxes, %s, %s", shapes[_i % 3], _i < 3 ? "FLIP" : "APIC");
  expect_same(a, b, na, 2, tb, what);
  free(a);
  free(b);
}
END_TEST

/* The column (plane, or 4 units along z) flowing past a turning disc with
 * friction and onto a free plate: the point fields and every step's force
 * and torque on both bodies after 150 steps on nthreads threads. */
static double *run_bodies(int i, int nthreads, size_t *len, int *team)
{
  *team = use_threads(nthreads);
  mpm_config c;
  sim_config_column(&c, "ugimp", i ? 4 : 0, "mu_i");
  c.fill[0].ymin = 0.0101;
  c.nbody = 2;
  mpm_body_config *b = c.body;
  memset(b, 0, 2 * sizeof *b);
  for (int k = 0; k < 2; k++) {
    for (int d = 0; d < MPM_BODY_NDOF; d++)
      b[k].nval[d] = 1;
    b[k].axis = 2;
    b[k].cz = 0.02;
  }
  strcpy(b[0].name, "disc");
  b[0].shape = MPM_BODY_DISC;
  b[0].cx = 0.06;                               /* beside the column's foot */
  b[0].cy = 0.018;
  b[0].radius = 0.008;
  b[0].val[MPM_BODY_OMEGA][0] = 3.0;
  b[0].contact = MPM_CONTACT_FRICTION;
  b[0].friction = 0.4;
  strcpy(b[1].name, "plate");
  b[1].shape = MPM_BODY_BOX;
  b[1].cx = 0.03;
  b[1].cy = 0.0055;                             /* up to y = 0.0101: the nodes at 0.01 */
  b[1].hx = 0.03;
  b[1].hy = 0.0046;
  b[1].free[MPM_BODY_VY] = b[1].free[MPM_BODY_OMEGA] = 1;
  b[1].mass = 0.5;
  b[1].inertia = 1e-4;
  b[1].damping = 20.0;
  b[1].force[1] = 0.5 * 9.8;                    /* floating until the column lands */
  mpm_sim *s = NULL;
  mpm_err err = {0};
  ck_assert_msg(mpm_sim_create(&s, &c, &err) == MPM_OK, "%s", err.msg);
  enum { NSTEP = 150 };
  double forces[NSTEP][2][6];
  for (int k = 0; k < NSTEP; k++) {
    ck_assert_msg(mpm_sim_step(s, &err) == MPM_OK, "step %d: %s", k, err.msg);
    for (int j = 0; j < 2; j++)
      for (int d = 0; d < 3; d++) {
        forces[k][j][d] = s->body[j].s.f[d];
        forces[k][j][3 + d] = s->body[j].s.tq[d];
      }
  }
  double touched[2] = {0.0, 0.0};
  for (int k = 0; k < NSTEP; k++)
    for (int j = 0; j < 2; j++)
      touched[j] = fmax(touched[j], hypot(forces[k][j][0], forces[k][j][1]));
  ck_assert_msg(touched[0] > 0.0 && touched[1] > 0.0, "disc %g, plate %g N/m", touched[0],
                touched[1]);
  const mpm_points *P = s->pts;
  const double *f[] = {P->x, P->y, P->vx, P->vy, P->sxx, P->syy, P->sxy};
  const size_t nf = sizeof f / sizeof f[0], n = P->n, nb = sizeof forces / sizeof(double);
  double *out = malloc((nf * n + nb) * sizeof *out);
  ck_assert_ptr_nonnull(out);
  for (size_t k = 0; k < nf; k++)
    memcpy(out + k * n, f[k], n * sizeof *out);
  memcpy(out + nf * n, forces, sizeof forces);
  *len = nf * n + nb;
  mpm_sim_free(s);
  return out;
}

START_TEST(t_bodies_thread_count)
{
  size_t na, nb;
  int ta, tb;
  double *a = run_bodies(_i, 1, &na, &ta);
  double *b = run_bodies(_i, 2, &nb, &tb);
  ck_assert_uint_eq(na, nb);
  expect_same(a, b, na, 2, tb, _i ? "bodies, boxes" : "bodies, plane");
  free(a);
  free(b);
}
END_TEST

int main(void)
{
  const int team = threads_apart(2);
  if (team < 2) {
    const char *limit = getenv("OMP_THREAD_LIMIT");
#ifdef _OPENMP
    printf("test_threads: a parallel region asked for 2 threads ran on %d (OMP_THREAD_LIMIT %s%s):"
           " no run was compared across thread counts; skipped\n", team,
           limit ? "= " : "unset", limit ? limit : "");
#else
    (void)limit;
    printf("test_threads: built without OpenMP, one thread only: no run was compared across "
           "thread counts; skipped\n");
#endif
    return 77;
  }
  Suite *su = suite_create("threads");
  TCase *tc = tcase_create("threads");
  tcase_add_test(tc, t_q4_thread_count);
  tcase_add_test(tc, t_t3_thread_count);
  tcase_add_test(tc, t_q4_delta_thread_count);
  tcase_add_test(tc, t_t3_delta_thread_count);
  tcase_add_test(tc, t_ngf_extent_thread_count);
  tcase_add_test(tc, t_ngf_centre_thread_count);
  tcase_add_test(tc, t_density_thread_count);
  tcase_add_loop_test(tc, t_box_thread_count, 0, 6);
  tcase_add_loop_test(tc, t_bodies_thread_count, 0, 2);
  suite_add_tcase(su, tc);
  SRunner *sr = srunner_create(su);
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf == 0 ? 0 : 1;
}
