/* test_field.c: the NGF element field of one (sub)step and its diffusion
 * solvers (src/nonlocal/field.h).
 *
 * Checked from the definitions:
 *   - the solver table and its names agree (every kind has its entry);
 *   - explicit: mpm_nonlocal_field gives bitwise the dense flags, g_e,
 *     lap_e and isp_e of the steps it stands for (the model's dense rule,
 *     mpm_nonlocal_average, mpm_nonlocal_laplacian, mpm_nonlocal_pressure),
 *     so the solver step it replaced is unchanged;
 *   - implicit: lap_e = L_h g* with (I - c L_h) g* = g_e, checked as the
 *     residual of that equation with L_h applied by the explicit operator,
 *     c = (dt_sub / t0) A^2 d^2; relative to max g_e it is a sum of a few
 *     terms of size c |L_h| g ~ 1e2 g, so 1e-12 leaves round-off room;
 *   - a step without a dense point has nothing to diffuse: lap_e = 0, no error;
 *   - the model's hooks: a nonlocal model names its dense rule, a seeding
 *     model its local model and its seed.
 * The cloud: a 6 x 5 mesh of Q4 units, a no-slip floor (Dirichlet g), free
 * elsewhere; 2 x 2 points per unit in the lower four rows, loaded
 * lithostatically (p = 1e3 (4 - y)), with g varying in x and y; the top row
 * of points is loose (rho < rho_c), so its units are empty. */
#include <check.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/config.h"
#include "core/points.h"
#include "material/material.h"
#include "mesh/mesh.h"
#include "nonlocal/field.h"
#include "nonlocal/implicit.h"
#include "nonlocal/nonlocal.h"

enum { NX = 6, NY = 5 };

static mpm_mesh make_mesh(void)
{
  mpm_mesh m = {.nx = NX, .ny = NY, .x0 = 0.0, .y0 = 0.0, .dx = 0.1, .dy = 0.1,
                .topology = MPM_TOPO_Q4};
  mpm_err err = {0};
  ck_assert_int_eq(mpm_mesh_setup(&m, &err), MPM_OK);
  return m;
}

static mpm_material_params ngf_params(int p_sample)
{
  mpm_config cfg;
  memset(&cfg, 0, sizeof cfg);
  mpm_material_config_dk15(&cfg);
  cfg.material.E = 1e6;
  cfg.material.A = 0.48;
  cfg.material.t0 = 1e-3;
  cfg.material.p_sample = p_sample;
  mpm_material_params par;
  mpm_material_params_from_config(&par, &cfg);
  return par;
}

/* 2 x 2 points per unit in rows 0 ... 3; row 3 loose, with zero stress
 * (stress free, not dense). loose: every point loose. */
static mpm_points *make_points(const mpm_mesh *m, int loose)
{
  mpm_points *P = mpm_points_alloc(0);
  for (int j = 0; j < 4; j++)
    for (int i = 0; i < NX; i++)
      for (int k = 0; k < 4; k++) {
        size_t p;
        ck_assert_int_eq(mpm_points_push(P, &p), MPM_OK);
        P->x[p] = m->x0 + (i + 0.25 + 0.5 * (k % 2)) * m->dx;
        P->y[p] = m->y0 + (j + 0.25 + 0.5 * (k / 2)) * m->dy;
        P->mass[p] = 1.0 + 0.1 * k;
        int dense = !loose && j < 3;
        P->vol[p] = P->mass[p] / (dense ? 1600.0 : 1400.0);
        double pr = dense ? 1e3 * (4.0 - P->y[p] / m->dy) : 0.0;
        P->sxx[p] = P->syy[p] = P->szz[p] = -pr;
        P->sxy[p] = 0.1 * pr;
        P->g[p] = 1.0 + 0.5 * i + 0.25 * j * j + 0.01 * k;
      }
  return P;
}

static mpm_nonlocal *make_ws(const mpm_mesh *m, const mpm_points *P)
{
  const int edge[4] = {MPM_BC_FREE, MPM_BC_FREE, MPM_BC_NOSLIP, MPM_BC_FREE};
  mpm_nonlocal *ws = NULL;
  mpm_err err = {0};
  ck_assert_int_eq(mpm_nonlocal_alloc(&ws, m, edge, MPM_NONLOCAL_CENTRE, P->n, &err), MPM_OK);
  ck_assert_int_eq(mpm_nonlocal_locate(ws, m, P, &err), MPM_OK);
  return ws;
}

START_TEST(t_table)
{
  for (int k = 0; mpm_nonlocal_diffusion_table[k]; k++) {
    const char *name = mpm_nonlocal_diffusion_table[k]->name;
    ck_assert_str_eq(mpm_nonlocal_diffusion_name(k), name);
    ck_assert_int_eq(mpm_nonlocal_diffusion_from_name(name), k);
    /* a (sub)step solver has a laplacian; the steady one solves per step instead */
    ck_assert_int_eq(mpm_nonlocal_diffusion_table[k]->laplacian == NULL,
                     mpm_nonlocal_diffusion_table[k]->steady);
  }
  ck_assert_int_eq(mpm_nonlocal_diffusion_from_name("explicit"), MPM_DIFFUSION_EXPLICIT);
  ck_assert_int_eq(mpm_nonlocal_diffusion_from_name("implicit"), MPM_DIFFUSION_IMPLICIT);
  ck_assert_int_eq(mpm_nonlocal_diffusion_table[MPM_DIFFUSION_EXPLICIT]->stability_limited, 1);
  ck_assert_int_eq(mpm_nonlocal_diffusion_table[MPM_DIFFUSION_IMPLICIT]->stability_limited, 0);
  ck_assert_int_eq(mpm_nonlocal_diffusion_from_name("crank-nicolson"), -1);
  ck_assert_int_eq(mpm_nonlocal_diffusion_from_name("steady"), MPM_DIFFUSION_STEADY);
  ck_assert_int_eq(mpm_nonlocal_diffusion_table[MPM_DIFFUSION_STEADY]->steady, 1);
  ck_assert_ptr_null(mpm_nonlocal_diffusion_name(3));
  ck_assert_ptr_null(mpm_nonlocal_diffusion_name(-1));
  mpm_mesh m = make_mesh();
  mpm_points *P = make_points(&m, 0);
  mpm_nonlocal *ws = make_ws(&m, P);
  mpm_err err = {0};
  ck_assert_int_eq(mpm_nonlocal_set_diffusion(ws, 7, &err), MPM_EINVAL);
  mpm_nonlocal_free(ws);
  mpm_points_free(P);
}
END_TEST

/* Explicit: bitwise the steps it stands for, with each p sampling. */
START_TEST(t_explicit_is_the_steps)
{
  mpm_mesh m = make_mesh();
  mpm_points *P = make_points(&m, 0);
  const size_t nu = NX * NY;
  for (int sample = 0; sample < 2; sample++) {
    mpm_material_params par = ngf_params(sample);
    mpm_nonlocal *a = make_ws(&m, P), *b = make_ws(&m, P);
    mpm_err err = {0};
    ck_assert_int_eq(mpm_nonlocal_field(a, &mpm_material_ngf, &par, P, NULL, 1e-4, 0, &err),
                     MPM_OK);
    for (size_t p = 0; p < P->n; p++) {
      mpm_sym3 sig = {P->sxx[p], P->syy[p], P->szz[p], P->sxy[p], 0.0, 0.0};
      b->dense[p] = (unsigned char)mpm_material_ngf_dense(&par, sig, P->mass[p] / P->vol[p]);
      b->pn[p] = mpm_sym3_pressure(sig);
      ck_assert_int_eq(a->dense[p], b->dense[p]);
      ck_assert_int_eq(a->dense[p], P->y[p] < 0.3);
    }
    mpm_nonlocal_average(b, P->n, P->mass, P->g, b->dense);
    mpm_nonlocal_laplacian(b);
    if (sample == MPM_NGF_P_UNIT)
      mpm_nonlocal_pressure(b, P->n, P->mass, b->pn, b->dense);
    ck_assert_mem_eq(a->ge, b->ge, nu * sizeof(double));
    ck_assert_mem_eq(a->lap, b->lap, nu * sizeof(double));
    ck_assert_mem_eq(a->isp, b->isp, nu * sizeof(double));
    mpm_nonlocal_free(a);
    mpm_nonlocal_free(b);
  }
  mpm_points_free(P);
}
END_TEST

/* Implicit: (I - c L_h) g* = g_e on the filled units and lap_e = L_h g*. */
START_TEST(t_implicit_residual)
{
  mpm_mesh m = make_mesh();
  mpm_points *P = make_points(&m, 0);
  mpm_material_params par = ngf_params(0);
  const double dt = 5e-3;  /* c = 5 (0.48 * 5e-3)^2 = 2.9e-5 m^2: c 8/dx^2 = 0.023 */
  const double c = mpm_material_ngf_diffusivity(&par, dt);
  ck_assert_double_eq_tol(c, dt / 1e-3 * 0.48 * 0.48 * 0.005 * 0.005, 1e-20);
  mpm_nonlocal *ws = make_ws(&m, P), *chk = make_ws(&m, P);
  mpm_err err = {0};
  ck_assert_int_eq(mpm_nonlocal_set_diffusion(ws, MPM_DIFFUSION_IMPLICIT, &err), MPM_OK);
  for (int big = 0; big < 2; big++) {
    const double h = big ? 1e3 * dt : dt;  /* c |L_h| = 0.023 and 23 */
    const double ch = mpm_material_ngf_diffusivity(&par, h);
    ck_assert_int_eq(mpm_nonlocal_field(ws, &mpm_material_ngf, &par, P, NULL, h, 0, &err), MPM_OK);
    const double *gs = mpm_nonlocal_implicit_gstar(ws->diffusion_state);
    /* L_h g* by the explicit operator on the same filled units */
    memcpy(chk->sm, ws->sm, NX * NY * sizeof(double));
    memcpy(chk->ge, gs, NX * NY * sizeof(double));
    mpm_nonlocal_laplacian(chk);
    double gmax = 0.0;
    for (int e = 0; e < NX * NY; e++)
      gmax = fmax(gmax, ws->ge[e]);
    for (int e = 0; e < NX * NY; e++) {
      if (!(ws->sm[e] > 0.0)) {
        ck_assert_double_eq(ws->lap[e], 0.0);
        continue;
      }
      ck_assert_int_lt(e, 3 * NX);                      /* rows 0 ... 2 only */
      ck_assert_double_le(fabs(gs[e] - ch * chk->lap[e] - ws->ge[e]), 1e-12 * gmax);
      ck_assert_double_le(fabs(ch * (ws->lap[e] - chk->lap[e])), 1e-12 * gmax);
    }
  }
  mpm_linalg_stats st = mpm_nonlocal_implicit_stats(ws->diffusion_state);
  ck_assert_int_eq(st.analyses, 1);  /* the same filled units both times */
  ck_assert_int_eq(st.factors, 2);   /* two values of c */
  mpm_nonlocal_free(ws);
  mpm_nonlocal_free(chk);
  mpm_points_free(P);
}
END_TEST

/* No dense point: nothing to diffuse, lap_e = 0 everywhere, no error. */
START_TEST(t_implicit_nothing_dense)
{
  mpm_mesh m = make_mesh();
  mpm_points *P = make_points(&m, 1);
  mpm_material_params par = ngf_params(0);
  mpm_nonlocal *ws = make_ws(&m, P);
  mpm_err err = {0};
  ck_assert_int_eq(mpm_nonlocal_set_diffusion(ws, MPM_DIFFUSION_IMPLICIT, &err), MPM_OK);
  for (int e = 0; e < NX * NY; e++)
    ws->lap[e] = 1.0;
  ck_assert_int_eq(mpm_nonlocal_field(ws, &mpm_material_ngf, &par, P, NULL, 1e-3, 0, &err), MPM_OK);
  for (int e = 0; e < NX * NY; e++)
    ck_assert_double_eq(ws->lap[e], 0.0);
  mpm_nonlocal_free(ws);
  mpm_points_free(P);
}
END_TEST

/* The hooks the solver step calls instead of naming a model. */
START_TEST(t_model_hooks)
{
  for (int k = 0; mpm_material_table[k]; k++) {
    const mpm_material_type *t = mpm_material_table[k];
    if (t->nonlocal)
      ck_assert_msg(t->dense != NULL, "nonlocal model '%s' has no dense rule", t->name);
    ck_assert_msg(!t->before_seed == !t->seed, "model '%s': seed and local model go together",
                  t->name);
    if (t->before_seed)
      ck_assert_msg(!t->before_seed->nonlocal && !t->before_seed->before_seed,
                    "model '%s' seeds from a local model without a seeding phase", t->name);
  }
  ck_assert_ptr_eq(mpm_material_ngf.before_seed, &mpm_material_mu_i);
}
END_TEST

int main(void)
{
  Suite *s = suite_create("field");
  TCase *tc = tcase_create("field");
  tcase_add_test(tc, t_table);
  tcase_add_test(tc, t_explicit_is_the_steps);
  tcase_add_test(tc, t_implicit_residual);
  tcase_add_test(tc, t_implicit_nothing_dense);
  tcase_add_test(tc, t_model_hooks);
  suite_add_tcase(s, tc);
  SRunner *sr = srunner_create(s);
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf ? EXIT_FAILURE : EXIT_SUCCESS;
}
