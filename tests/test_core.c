/* test_core.c: unit tests of the core module (tensor helpers, point store,
 * error context) and of the elastic Jaumann update (MODEL.md sections 1, 2). */
#include <check.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/points.h"
#include "core/tensor3.h"
#include "material/material.h"

/* Values below are O(1); sums of a few products lose at most a few ulps, so
 * 1e-14 absolute is a round-off bound with margin. */
#define EPS 1e-14

static mpm_sym3 sample_stress(void)
{
  return (mpm_sym3){-3.0, -1.5, -2.0, 0.7, 0.0, 0.0};
}

START_TEST(t_invariants)
{
  mpm_sym3 s = sample_stress();
  double p = mpm_sym3_pressure(s);
  ck_assert_double_eq_tol(p, 6.5 / 3.0, EPS);                 /* p = -tr/3 */
  mpm_sym3 d = mpm_sym3_dev(s);
  ck_assert_double_eq_tol(mpm_sym3_trace(d), 0.0, EPS);
  /* tau^2 = s0:s0/2 = (s0xx^2 + s0yy^2 + s0zz^2)/2 + sxy^2 */
  double e = (d.xx * d.xx + d.yy * d.yy + d.zz * d.zz) / 2 + 0.49;
  ck_assert_double_eq_tol(mpm_sym3_tau(s), sqrt(e), EPS);
  /* pure shear sxy = t: tau = t */
  mpm_sym3 sh = {0, 0, 0, 0.25, 0, 0};
  ck_assert_double_eq_tol(mpm_sym3_tau(sh), 0.25, EPS);
}
END_TEST

START_TEST(t_sym_skw)
{
  mpm_mat3 L = {{{1.0, 2.0, 0.0}, {-0.5, 3.0, 0.0}, {0.0, 0.0, 0.0}}};
  mpm_sym3 D = mpm_mat3_sym(&L);
  mpm_mat3 W = mpm_mat3_skw(&L);
  ck_assert_double_eq_tol(D.xy, 0.75, EPS);
  ck_assert_double_eq_tol(W.m[0][1], 1.25, EPS);
  ck_assert_double_eq_tol(W.m[1][0], -1.25, EPS);
  /* D + W = L componentwise */
  mpm_mat3 Df = mpm_sym3_full(D);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      ck_assert_double_eq_tol(Df.m[i][j] + W.m[i][j], L.m[i][j], EPS);
}
END_TEST

/* The Jaumann term W s - s W is the rate of change of s under rigid spin, so
 * it leaves the invariants unchanged: tr(Ws - sW) = 0 and s:(Ws - sW) = 0. */
START_TEST(t_spin_objective)
{
  mpm_sym3 s = sample_stress();
  s.yz = 0.3;
  s.zx = -0.2;
  mpm_mat3 W = {{{0.0, 0.4, -0.1}, {-0.4, 0.0, 0.6}, {0.1, -0.6, 0.0}}};
  mpm_sym3 r = mpm_sym3_spin(&W, s);
  ck_assert_double_eq_tol(mpm_sym3_trace(r), 0.0, EPS);
  ck_assert_double_eq_tol(mpm_sym3_ddot(s, r), 0.0, 1e-13);
  /* 2D check by hand: W = w(e_x e_y - e_y e_x), s = diag(a, b): (Ws - sW)_xy = w (b - a) */
  mpm_mat3 W2 = {{{0.0, 0.5, 0.0}, {-0.5, 0.0, 0.0}, {0.0, 0.0, 0.0}}};
  mpm_sym3 d = {2.0, -1.0, 0.0, 0.0, 0.0, 0.0};
  ck_assert_double_eq_tol(mpm_sym3_spin(&W2, d).xy, 0.5 * (-1.0 - 2.0), EPS);
}
END_TEST

/* The closed form equals W s - s W multiplied out in full, for random skew W
 * and symmetric s (all six components non-zero). */
START_TEST(t_spin_definition)
{
  unsigned long long state = 12345;
  for (int trial = 0; trial < 200; trial++) {
    double v[9];
    for (int k = 0; k < 9; k++) {
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;
      v[k] = (double)(state >> 11) / 9007199254740992.0 * 2.0 - 1.0;  /* [-1, 1) */
    }
    mpm_sym3 s = {v[0], v[1], v[2], v[3], v[4], v[5]};
    mpm_mat3 W = {{{0.0, v[6], -v[8]}, {-v[6], 0.0, v[7]}, {v[8], -v[7], 0.0}}};
    mpm_mat3 S = mpm_sym3_full(s), R;
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++) {
        R.m[i][j] = 0.0;
        for (int k = 0; k < 3; k++)
          R.m[i][j] += W.m[i][k] * S.m[k][j] - S.m[i][k] * W.m[k][j];
      }
    mpm_sym3 r = mpm_sym3_spin(&W, s);
    const double want[6] = {R.m[0][0], R.m[1][1], R.m[2][2], R.m[0][1], R.m[1][2], R.m[2][0]};
    const double got[6] = {r.xx, r.yy, r.zz, r.xy, r.yz, r.zx};
    for (int k = 0; k < 6; k++)
      ck_assert_double_eq_tol(got[k], want[k], 1e-15 * 8);  /* |entries| <= 1: a few ulps of 4 */
    ck_assert_double_eq_tol(R.m[1][0], R.m[0][1], 1e-15);   /* the full product is symmetric */
  }
}
END_TEST

START_TEST(t_elastic_operator)
{
  double G = 3.0, K = 5.0;
  mpm_sym3 D = {0.1, -0.2, 0.0, 0.05, 0.0, 0.0};
  mpm_sym3 c = mpm_sym3_elastic(D, G, K);
  /* tr(C:D) = 3K tr(D); dev part = 2G D0 */
  ck_assert_double_eq_tol(mpm_sym3_trace(c), 3 * K * (-0.1), EPS);
  ck_assert_double_eq_tol(c.xy, 2 * G * 0.05, EPS);
}
END_TEST

/* One elastic step under uniaxial strain rate: sigma_yy += dt (K + 4G/3) Dyy,
 * sigma_xx = sigma_zz += dt (K - 2G/3) Dyy. */
START_TEST(t_elastic_update)
{
  mpm_material_params par = {.E = 1e6, .nu = 0.3};
  mpm_material_params_derive(&par);
  ck_assert_double_eq_tol(par.G, 1e6 / 2.6, 1e-8);
  ck_assert_double_eq_tol(par.K, 1e6 / 1.2, 1e-8);
  mpm_mat3 L = {{{0, 0, 0}, {0, -0.01, 0}, {0, 0, 0}}};
  mpm_mpoint pt = {.sigma = mpm_sym3_zero(), .rho = 1500};
  mpm_material_elastic.update_point(&par, &L, 1e-3, &pt, NULL);
  double dyy = -0.01 * 1e-3;
  ck_assert_double_eq_tol(pt.sigma.yy, (par.K + 4 * par.G / 3) * dyy, 1e-9);
  ck_assert_double_eq_tol(pt.sigma.xx, (par.K - 2 * par.G / 3) * dyy, 1e-9);
  ck_assert_double_eq_tol(pt.sigma.zz, pt.sigma.xx, 1e-12);
  ck_assert_int_eq(pt.state, MPM_STATE_DENSE);
  ck_assert_ptr_eq(mpm_material_lookup("elastic"), &mpm_material_elastic);
  ck_assert_ptr_null(mpm_material_lookup("no-such-model"));
}
END_TEST

START_TEST(t_points_store)
{
  mpm_points *P = mpm_points_alloc(2);
  ck_assert_ptr_nonnull(P);
  for (int k = 0; k < 100; k++) {
    size_t i;
    ck_assert_int_eq(mpm_points_push(P, &i), MPM_OK);
    ck_assert_uint_eq(i, (size_t)k);
    P->x[i] = k;
    P->sxy[i] = -k;
  }
  ck_assert_uint_eq(P->n, 100);
  ck_assert_uint_ge(P->cap, 100);
  unsigned char keep[100];
  for (int k = 0; k < 100; k++)
    keep[k] = (unsigned char)(k % 3 != 0);        /* drop 0, 3, 6, ... (34 points) */
  mpm_points_compact(P, keep);
  ck_assert_uint_eq(P->n, 66);
  ck_assert_double_eq(P->x[0], 1.0);
  ck_assert_double_eq(P->x[2], 4.0);
  ck_assert_double_eq(P->sxy[65], -98.0);
  ck_assert_int_eq(P->id[65], 98);
  size_t j;
  mpm_points_push(P, &j);
  ck_assert_int_eq(P->id[j], 100);                 /* ids are never reused */
  ck_assert_double_eq(P->x[j], 0.0);
  mpm_points_free(P);
  mpm_points_free(NULL);
}
END_TEST

START_TEST(t_errors)
{
  mpm_err e = {0};
  int rc = mpm_err_set(&e, MPM_EINPUT, "key '%s' = %d", "mesh.nx", -3);
  ck_assert_int_eq(rc, MPM_EINPUT);
  ck_assert_int_eq(e.code, MPM_EINPUT);
  ck_assert_str_eq(e.msg, "key 'mesh.nx' = -3");
  ck_assert_str_eq(mpm_err_string(MPM_EOUTSIDE), "material point left the mesh");
  ck_assert_str_eq(mpm_err_string(9999), "unknown error");
  mpm_err_clear(&e);
  ck_assert_int_eq(e.code, MPM_OK);
  ck_assert_int_eq(mpm_err_set(NULL, MPM_EIO, "x"), MPM_EIO);
  /* context put before the message from below, code replaced */
  mpm_err_set(&e, MPM_EINVAL, "linalg: singular");
  ck_assert_int_eq(mpm_err_prefix(&e, MPM_ESOLVE, "step %d, t = %g s", 7, 0.5), MPM_ESOLVE);
  ck_assert_int_eq(e.code, MPM_ESOLVE);
  ck_assert_str_eq(e.msg, "step 7, t = 0.5 s: linalg: singular");
  ck_assert_int_eq(mpm_err_prefix(NULL, MPM_EIO, "x"), MPM_EIO);
}
END_TEST

int main(void)
{
  Suite *s = suite_create("core");
  TCase *tc = tcase_create("core");
  tcase_add_test(tc, t_invariants);
  tcase_add_test(tc, t_sym_skw);
  tcase_add_test(tc, t_spin_objective);
  tcase_add_test(tc, t_spin_definition);
  tcase_add_test(tc, t_elastic_operator);
  tcase_add_test(tc, t_elastic_update);
  tcase_add_test(tc, t_points_store);
  tcase_add_test(tc, t_errors);
  suite_add_tcase(s, tc);
  SRunner *sr = srunner_create(s);
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf ? EXIT_FAILURE : EXIT_SUCCESS;
}
