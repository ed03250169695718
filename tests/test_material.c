/* test_material.c: conformance of every constitutive model in
 * mpm_material_table (MODEL.md sections 1, 4 and 5).
 *
 * Each model of the table, whatever its name, goes through the same checks
 * (a model added to the table is picked up by the loops, nothing here names
 * the models except the key lists of check 4):
 *
 * The update that takes the fluidity of a steady solve (update_steady, MODEL.md
 * section 6) is checked as one more model where a model has one.
 *
 *  1. Frame indifference: the update commutes with a rotation Q about z,
 *     update(Q sigma Q^T, Q L Q^T) = Q update(sigma, L) Q^T, with g, gdot_p
 *     and the state unchanged, for states below and above yield, loose, in
 *     tension and with out-of-plane components, at several angles. Every
 *     model is built from tensors (C:D, W sigma - sigma W) and invariants
 *     (p, tau); a component used where a tensor or an invariant is meant
 *     breaks it by O(dt |L| |sigma|).
 *  2. Zero stays zero: sigma = 0, L = 0 gives sigma = 0 exactly, gdot_p = 0
 *     and g = 0 for any dt and density (the state may be either).
 *  3. Elastic response: below yield, one step is the Jaumann hypoelastic
 *     increment dt (2G D0 + K tr(D) I + W sigma - sigma W), with G and K and
 *     the spin term computed here by hand from E, nu and full 3x3 products.
 *  4. Parameter check: NaN in any key the model reads gives MPM_EINPUT with a
 *     message naming that key; a model without a key list here fails.
 *  5. The batch update the step calls (mpm_material_type.update, its kernel
 *     inlined into a vectorised loop once per dimension) is the point update
 *     (update_point) point by point, bitwise: plane-strain points (L and the
 *     stress in the plane) and 3D points (full L), every model, the
 *     hyperelastic one with its F and Fp.
 *
 * Material: [DK15] Table 1 through mpm_material_config_dk15 and
 * mpm_material_params_from_config, E = 1e6 Pa (G = 3.85e5 Pa, K = 8.33e5 Pa)
 * so that the steps below stay small against p = 1 kPa, and the NGF values
 * of [DK-silo], A = 0.48, t0 = 1e-3 s. The NGF update also reads pt->g (g_n),
 * pt->lap (lap of g of the point's unit) and pt->isp (0: its own p_tr^-1/2);
 * every model gets them, the others ignore them. Checks 1 and 3 run once per
 * NGF form (dk, hs21); the other models ignore the form.
 *
 * Tolerances. Stress: 1e-12 relative to the largest stress component of the
 * problem. The two sides of each comparison are the same sums of O(10) terms
 * of size <= |sigma| (rotation: 9 products per component, |Q_ij| <= 1, done
 * twice; update: trial sum, return scaling by invariants computed to a few
 * ulp), taken in a different order, so they differ by O(10-100) eps |sigma|
 * ~ 1e-15 to 2e-14 |sigma|; 1e-12 leaves a margin of 50 or more. The
 * smallest effect checked, the spin term of check 3, is dt |W| |sigma0| ~
 * 1e-4 |sigma|, eight decades above. Rates (g, gdot_p): 1e-12 relative to
 * the larger of the two values and |L| (the scale of both; g = gdot_p / mu).
 * Exact zeros (check 2, gdot_p and g below yield) are compared with ==. */
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/config.h"
#include "core/points.h"
#include "core/tensor3.h"
#include "material/material.h"

#define TOL 1e-12
#define P0 1000.0     /* reference pressure [Pa] */
#define RHO_D 1550.0  /* dense: above rho_c = 1500 kg/m^3 */
#define RHO_L 1400.0  /* loose: below rho_c */

/* [DK15] Table 1 with Young's modulus E, [DK-silo] A and t0, NGF form. */
static mpm_material_params table1(double E, int form)
{
  mpm_config cfg;
  memset(&cfg, 0, sizeof cfg);
  mpm_material_config_dk15(&cfg);
  cfg.material.E = E;
  cfg.material.A = 0.48;
  cfg.material.t0 = 1e-3;
  cfg.material.form = form;
  cfg.material.p_sample = MPM_NGF_P_POINT;
  cfg.material.t_seed = 0.0;
  mpm_material_params par;
  mpm_material_params_from_config(&par, &cfg);
  return par;
}

/* ------------------------------------------------------------ helpers */

static double sym3_maxabs(mpm_sym3 s)
{
  double v[6] = {s.xx, s.yy, s.zz, s.xy, s.yz, s.zx}, m = 0.0;
  for (int i = 0; i < 6; i++)
    m = fabs(v[i]) > m ? fabs(v[i]) : m;
  return m;
}

static double mat3_maxabs(const mpm_mat3 *A)
{
  double m = 0.0;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      m = fabs(A->m[i][j]) > m ? fabs(A->m[i][j]) : m;
  return m;
}

static double sym3_dist(mpm_sym3 a, mpm_sym3 b)
{
  return sym3_maxabs(mpm_sym3_axpy(a, -1.0, b));
}

static int sym3_finite(mpm_sym3 s)
{
  return isfinite(s.xx) && isfinite(s.yy) && isfinite(s.zz) && isfinite(s.xy) &&
         isfinite(s.yz) && isfinite(s.zx);
}

/* A B */
static mpm_mat3 mat3_mul(const mpm_mat3 *A, const mpm_mat3 *B)
{
  mpm_mat3 C;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      double s = 0.0;
      for (int k = 0; k < 3; k++)
        s += A->m[i][k] * B->m[k][j];
      C.m[i][j] = s;
    }
  return C;
}

/* Q A Q^T */
static mpm_mat3 mat3_rotate(const mpm_mat3 *Q, const mpm_mat3 *A)
{
  mpm_mat3 QA = mat3_mul(Q, A), Qt;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      Qt.m[i][j] = Q->m[j][i];
  return mat3_mul(&QA, &Qt);
}

/* Symmetric part of A as an mpm_sym3. */
static mpm_sym3 sym3_of(const mpm_mat3 *A)
{
  return (mpm_sym3){A->m[0][0], A->m[1][1], A->m[2][2],
                    0.5 * (A->m[0][1] + A->m[1][0]),
                    0.5 * (A->m[1][2] + A->m[2][1]),
                    0.5 * (A->m[2][0] + A->m[0][2])};
}

static mpm_sym3 sym3_rotate(const mpm_mat3 *Q, mpm_sym3 s)
{
  mpm_mat3 S = mpm_sym3_full(s);
  mpm_mat3 R = mat3_rotate(Q, &S);
  return sym3_of(&R);
}

/* Rotation by th about z. */
static mpm_mat3 rot_z(double th)
{
  const double c = cos(th), s = sin(th);
  return (mpm_mat3){{{c, -s, 0.0}, {s, c, 0.0}, {0.0, 0.0, 1.0}}};
}

/* |a - b| within TOL relative to max(|a|, |b|, scale). */
static int rate_close(double a, double b, double scale)
{
  double m = fmax(fmax(fabs(a), fabs(b)), scale);
  return fabs(a - b) <= TOL * m;
}

static mpm_mpoint run(mpm_material_update_fn update, const mpm_material_params *par,
                      const mpm_mat3 *L, double dt, mpm_mpoint pt)
{
  update(par, L, dt, &pt, NULL);
  return pt;
}

/* Every update of the table: each model's update, and the update with the
 * fluidity of a steady solve where a model has one ("<model>/steady", which
 * reads pt->g as g_{n+1}). Checks 1-3 hold for all of them. */
typedef struct variant {
  char name[48];
  mpm_material_update_fn update;
} variant;

#define NVARIANT 16

static int variants(variant v[NVARIANT])
{
  int n = 0;
  for (const mpm_material_type *const *t = mpm_material_table; *t && n < NVARIANT - 1; t++) {
    if ((*t)->defgrad)
      continue;                 /* F and Fp, not a stress rate: tests/test_hyper.c */
    snprintf(v[n].name, sizeof v[n].name, "%s", (*t)->name);
    v[n++].update = (*t)->update_point;
    if ((*t)->update_steady_point) {
      snprintf(v[n].name, sizeof v[n].name, "%s/steady", (*t)->name);
      v[n++].update = (*t)->update_steady_point;
    }
  }
  return n;
}

/* ------------------------------------------- 1. frame indifference */

typedef struct obj_case {
  const char *what;
  mpm_sym3 sigma;  /* sigma_n */
  mpm_mat3 L;
  double rho, g, lap, isp, dt;
} obj_case;

/* Stresses around p = 1 kPa: tau/p ~ 0.08 (below mu_s = 0.38 of Table 1) and
 * ~ 0.46 (above mu_s, below mu_2 = 0.64); L mixes stretch (tr L < 0: the
 * point stays compressed), shear and spin of O(1) 1/s; dt = 1e-4 s gives
 * strain increments ~ 1e-4, stress increments ~ 40 Pa. */
#define SIG_LOW  {-P0 + 60.0, -P0 - 40.0, -P0 - 20.0, 50.0, 0.0, 0.0}
#define SIG_HIGH {-P0 + 150.0, -P0 - 120.0, -P0 - 30.0, 420.0, 0.0, 0.0}
#define L_PLANE  {{{0.3, 0.9, 0.0}, {-0.4, -0.5, 0.0}, {0.0, 0.0, 0.0}}}

static const obj_case obj_cases[] = {
  {"dense, below yield", SIG_LOW, L_PLANE, RHO_D, 0.0, 0.0, 0.0, 1e-4},
  {"dense, above yield, g_n > 0", SIG_HIGH, L_PLANE, RHO_D, 2.0, 30.0, 0.0, 1e-4},
  {"dense, above yield, g_n = 0, lap > 0, unit isp", SIG_HIGH, L_PLANE, RHO_D, 0.0, 2e5,
   0.031, 1e-4},
  {"dense, out-of-plane components", {-P0 + 150.0, -P0 - 120.0, -P0 - 30.0, 300.0, 90.0,
   -160.0}, {{{0.3, 0.9, 0.2}, {-0.4, -0.5, -0.6}, {0.25, -0.3, 0.1}}}, RHO_D, 1.5, 0.0,
   0.0, 1e-4},
  {"loose (rho < rho_c)", SIG_HIGH, L_PLANE, RHO_L, 2.0, 0.0, 0.0, 1e-4},
  {"tension (p_tr < 0)", {500.0, 400.0, 450.0, 100.0, 0.0, 0.0}, L_PLANE, RHO_D, 2.0, 0.0,
   0.0, 1e-4},
};

/* The stress cases are where they claim to be with respect to Table 1. */
START_TEST(t_cases_as_stated)
{
  const mpm_sym3 lo = SIG_LOW, hi = SIG_HIGH;
  ck_assert_double_lt(mpm_sym3_tau(lo) / mpm_sym3_pressure(lo), 0.25 * MPM_DK15_MU_S);
  ck_assert_double_gt(mpm_sym3_tau(hi) / mpm_sym3_pressure(hi), 1.1 * MPM_DK15_MU_S);
  ck_assert_double_lt(mpm_sym3_tau(hi) / mpm_sym3_pressure(hi), 0.9 * MPM_DK15_MU_2);
  ck_assert_double_lt(RHO_L, MPM_DK15_RHO_C);
  ck_assert_double_gt(RHO_D, MPM_DK15_RHO_C);
}
END_TEST

START_TEST(t_frame_indifference)
{
  variant v[NVARIANT];
  const int nv = variants(v);
  const double pi = acos(-1.0);
  const double angles[] = {0.3, pi / 6, pi / 2, 2.5, pi, -1.1, 4.0};
  const size_t ncase = sizeof obj_cases / sizeof obj_cases[0];
  const size_t nang = sizeof angles / sizeof angles[0];
  for (const variant *t = v; t < v + nv; t++)
    for (int form = 0; mpm_material_ngf_form_name(form); form++) {
      const mpm_material_params par = table1(1e6, form);
      for (size_t c = 0; c < ncase; c++) {
        const obj_case *oc = &obj_cases[c];
        const mpm_mpoint p0 = {.sigma = oc->sigma, .rho = oc->rho, .g = oc->g,
                               .lap = oc->lap, .isp = oc->isp};
        const mpm_mpoint a = run(t->update, &par, &oc->L, oc->dt, p0);
        ck_assert_msg(sym3_finite(a.sigma), "%s: %s: non-finite stress", t->name,
                      oc->what);
        const double ssc = fmax(sym3_maxabs(oc->sigma), sym3_maxabs(a.sigma));
        const double rsc = mat3_maxabs(&oc->L);
        for (size_t k = 0; k < nang; k++) {
          const mpm_mat3 Q = rot_z(angles[k]);
          mpm_mpoint pr = p0;
          pr.sigma = sym3_rotate(&Q, oc->sigma);
          const mpm_mat3 Lr = mat3_rotate(&Q, &oc->L);
          const mpm_mpoint b = run(t->update, &par, &Lr, oc->dt, pr);
          const double e = sym3_dist(b.sigma, sym3_rotate(&Q, a.sigma));
          ck_assert_msg(e <= TOL * ssc,
                        "%s (form %s): %s, theta = %g: |sigma(Q.Q^T) - Q sigma Q^T| = %g Pa"
                        " > %g Pa",
                        t->name, mpm_material_ngf_form_name(form), oc->what, angles[k], e,
                        TOL * ssc);
          ck_assert_msg(rate_close(a.g, b.g, rsc), "%s (form %s): %s, theta = %g: g %.17g vs %.17g",
                        t->name, mpm_material_ngf_form_name(form), oc->what, angles[k], a.g,
                        b.g);
          ck_assert_msg(rate_close(a.gdp, b.gdp, rsc),
                        "%s (form %s): %s, theta = %g: gdot_p %.17g vs %.17g", t->name,
                        mpm_material_ngf_form_name(form), oc->what, angles[k], a.gdp, b.gdp);
          ck_assert_msg(a.state == b.state, "%s (form %s): %s, theta = %g: state %d vs %d",
                        t->name, mpm_material_ngf_form_name(form), oc->what, angles[k], a.state,
                        b.state);
        }
      }
    }
}
END_TEST

/* ----------------------------------------------- 2. zero stays zero */

/* sigma = 0 and L = 0: the trial stress is exactly 0 (0 + dt (0 + 0)), so
 * no model has anything to create a stress from. elastic keeps sigma = 0 as a
 * dense point; mu_i and ngf see p_tr = 0 (not > 0) and disconnect it: sigma = 0,
 * gdot_p = sqrt(2 D0:D0) = 0, and ngf sets g = 0. */
START_TEST(t_zero_stays_zero)
{
  variant v[NVARIANT];
  const int nv = variants(v);
  const double dts[] = {0.0, 1e-7, 1e-4, 1.0, 1e3};
  const double rhos[] = {RHO_D, RHO_L};
  const mpm_mat3 L = {{{0.0}}};
  for (const variant *t = v; t < v + nv; t++) {
    const mpm_material_params par = table1(1e6, MPM_NGF_DK);
    for (size_t i = 0; i < sizeof dts / sizeof dts[0]; i++)
      for (size_t j = 0; j < sizeof rhos / sizeof rhos[0]; j++) {
        const mpm_mpoint p0 = {.sigma = mpm_sym3_zero(), .rho = rhos[j]};
        const mpm_mpoint a = run(t->update, &par, &L, dts[i], p0);
        const mpm_sym3 s = a.sigma;
        ck_assert_msg(s.xx == 0.0 && s.yy == 0.0 && s.zz == 0.0 && s.xy == 0.0 &&
                          s.yz == 0.0 && s.zx == 0.0,
                      "%s: dt = %g, rho = %g: sigma = (%g %g %g %g %g %g), not 0",
                      t->name, dts[i], rhos[j], s.xx, s.yy, s.zz, s.xy, s.yz, s.zx);
        ck_assert_msg(a.gdp == 0.0, "%s: dt = %g, rho = %g: gdot_p = %g, not 0",
                      t->name, dts[i], rhos[j], a.gdp);
        ck_assert_msg(a.g == 0.0, "%s: dt = %g, rho = %g: g = %g, not 0", t->name,
                      dts[i], rhos[j], a.g);
        ck_assert_msg(a.state == MPM_STATE_DENSE || a.state == MPM_STATE_DISCONNECTED,
                      "%s: state %d", t->name, a.state);
      }
  }
}
END_TEST

/* ------------------------------------------- 3. elastic response */

typedef struct el_case {
  const char *what;
  mpm_sym3 sigma;
  mpm_mat3 L;
} el_case;

/* D ~ 1e-2 1/s and dt = 1e-3 s: strain 1e-5, stress increment ~ 4 Pa, so
 * tau_tr/p_tr stays below 0.1 (mu_s = 0.38); spin 0.5 1/s rotates by 5e-4
 * rad: the spin term is ~ 0.1 Pa where sigma has a deviator. */
static const el_case el_cases[] = {
  {"hydrostatic", {-P0, -P0, -P0, 0.0, 0.0, 0.0},
   {{{-0.012, 0.008 + 0.5, 0.0}, {0.008 - 0.5, 0.006, 0.0}, {0.0, 0.0, 0.0}}}},
  {"hydrostatic + small deviator", SIG_LOW,
   {{{-0.012, 0.008 + 0.5, 0.0}, {0.008 - 0.5, 0.006, 0.0}, {0.0, 0.0, 0.0}}}},
  {"out-of-plane components", {-P0 + 40.0, -P0 - 30.0, -P0 - 10.0, 25.0, -35.0, 20.0},
   {{{-0.012, 0.5, 0.01}, {-0.49, 0.006, 0.3}, {-0.2, -0.31, -0.004}}}},
};

START_TEST(t_elastic_step)
{
  variant v[NVARIANT];
  const int nv = variants(v);
  const double dt = 1e-3, E = 1e6, nu = MPM_DK15_NU;
  const double G = E / (2.0 * (1.0 + nu)), K = E / (3.0 * (1.0 - 2.0 * nu));
  for (const variant *t = v; t < v + nv; t++)
    for (int form = 0; mpm_material_ngf_form_name(form); form++) {
      const mpm_material_params par = table1(E, form);
      for (size_t c = 0; c < sizeof el_cases / sizeof el_cases[0]; c++) {
        const el_case *ec = &el_cases[c];
        /* by hand: D, W, C:D = 2G D0 + K tr(D) I, W S - S W */
        mpm_mat3 D, W;
        for (int i = 0; i < 3; i++)
          for (int j = 0; j < 3; j++) {
            D.m[i][j] = 0.5 * (ec->L.m[i][j] + ec->L.m[j][i]);
            W.m[i][j] = 0.5 * (ec->L.m[i][j] - ec->L.m[j][i]);
          }
        const double trD = D.m[0][0] + D.m[1][1] + D.m[2][2];
        const mpm_mat3 S = mpm_sym3_full(ec->sigma);
        const mpm_mat3 WS = mat3_mul(&W, &S), SW = mat3_mul(&S, &W);
        mpm_mat3 rate;
        for (int i = 0; i < 3; i++)
          for (int j = 0; j < 3; j++)
            rate.m[i][j] = 2.0 * G * (D.m[i][j] - (i == j ? trD / 3.0 : 0.0))
                         + (i == j ? K * trD : 0.0) + WS.m[i][j] - SW.m[i][j];
        const mpm_sym3 want = mpm_sym3_axpy(ec->sigma, dt, sym3_of(&rate));
        ck_assert_double_lt(mpm_sym3_tau(want), 0.25 * MPM_DK15_MU_S * mpm_sym3_pressure(want));

        /* g_n = 0, lap = 0: ngf's g* = 0 and tau_tr < mu_2 p, where g = 0 is
         * kept (no spontaneous fluidisation), so tau = tau_tr */
        const mpm_mpoint p0 = {.sigma = ec->sigma, .rho = RHO_D};
        const mpm_mpoint a = run(t->update, &par, &ec->L, dt, p0);
        const double e = sym3_dist(a.sigma, want), tol = TOL * sym3_maxabs(ec->sigma);
        const mpm_sym3 df = mpm_sym3_axpy(a.sigma, -1.0, want);
        ck_assert_msg(e <= tol,
                      "%s (form %s): %s: |sigma - sigma_n - dt (C:D + W s - s W)| = %g Pa"
                      " > %g Pa (got - want: xx %g yy %g zz %g xy %g yz %g zx %g)",
                      t->name, mpm_material_ngf_form_name(form), ec->what, e, tol, df.xx, df.yy,
                      df.zz, df.xy, df.yz, df.zx);
        ck_assert_msg(a.gdp == 0.0, "%s: %s: gdot_p = %g below yield", t->name,
                      ec->what, a.gdp);
        ck_assert_msg(a.g == 0.0, "%s: %s: g = %g from g_n = 0, lap = 0", t->name,
                      ec->what, a.g);
        ck_assert_msg(a.state == MPM_STATE_DENSE, "%s: %s: state %d", t->name,
                      ec->what, a.state);
      }
    }
  /* the parameters used G and K as derived here */
  const mpm_material_params par = table1(E, MPM_NGF_DK);
  ck_assert_double_eq_tol(par.G, G, TOL * G);
  ck_assert_double_eq_tol(par.K, K, TOL * K);
}
END_TEST

/* --------------------------------------------- 4. parameter check */

/* The input keys (after "material.") each model reads. The test cannot ask a
 * model which parameters it uses, so they are stated here, next to the model
 * name, and a model of the table without an entry fails t_check_rejects_nan:
 * a new model must say which keys its check guards before it passes. Keys a
 * model does not read need not be rejected (elastic ignores the granular
 * ones). t_seed is read by the solver for ngf (local mu(I) before it) and
 * checked by the model. */
typedef struct model_keys {
  const char *model;
  const char *keys[16];  /* NULL ended */
} model_keys;

static const model_keys used_keys[] = {
  {"elastic", {"E", "nu", NULL}},
  {"mu_i", {"E", "nu", "rho_s", "rho_c", "mu_s", "mu_2", "I0", "d", NULL}},
  {"ngf", {"E", "nu", "rho_s", "rho_c", "mu_s", "mu_2", "I0", "d", "A", "t0", "t_seed",
           NULL}},
  {"ngf_hyper", {"E", "nu", "rho_s", "rho_c", "mu_s", "mu_2", "I0", "d", "A", "t0", "t_seed",
                 NULL}},
};

static const model_keys *keys_of(const char *model)
{
  for (size_t i = 0; i < sizeof used_keys / sizeof used_keys[0]; i++)
    if (strcmp(used_keys[i].model, model) == 0)
      return &used_keys[i];
  return NULL;
}

/* The input field of par for a key, NULL if the test does not know it. */
static double *param_field(mpm_material_params *par, const char *key)
{
  const char *const names[] = {"E", "nu", "rho_s", "rho_c", "mu_s", "mu_2",
                                      "I0", "d", "A", "t0", "t_seed"};
  double *const field[] = {&par->E, &par->nu, &par->rho_s, &par->rho_c, &par->mu_s,
                           &par->mu_2, &par->I0, &par->d, &par->A, &par->t0,
                           &par->t_seed};
  for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
    if (strcmp(names[i], key) == 0)
      return field[i];
  return NULL;
}

/* 1 if msg names "material.<key>" as a whole word (not a prefix of another key). */
static int names_key(const char *msg, const char *key)
{
  char want[64];
  snprintf(want, sizeof want, "material.%s", key);
  const size_t n = strlen(want);
  for (const char *s = strstr(msg, want); s; s = strstr(s + 1, want)) {
    const char next = s[n];
    if (!(next == '_' || (next >= '0' && next <= '9') || (next >= 'a' && next <= 'z') ||
          (next >= 'A' && next <= 'Z')))
      return 1;
  }
  return 0;
}

START_TEST(t_check_rejects_nan)
{
  for (const mpm_material_type *const *t = mpm_material_table; *t; t++) {
    const model_keys *mk = keys_of((*t)->name);
    ck_assert_msg(mk != NULL,
                  "material model '%s' has no key list in tests/test_material.c"
                  " (used_keys): add the keys it reads", (*t)->name);
    if (!mk->keys[0])
      continue;
    ck_assert_msg((*t)->check != NULL, "material model '%s' reads %s but has no check",
                  (*t)->name, mk->keys[0]);
    const mpm_material_params base = table1(1e6, MPM_NGF_DK);
    mpm_err err = {0};
    ck_assert_msg((*t)->check(&base, &err) == MPM_OK, "%s: Table 1 rejected: %s",
                  (*t)->name, err.msg);
    for (const char *const *k = mk->keys; *k; k++) {
      mpm_material_params par = base;
      double *f = param_field(&par, *k);
      ck_assert_msg(f != NULL, "key list of '%s': unknown key '%s'", (*t)->name, *k);
      *f = NAN;
      mpm_material_params_derive(&par);
      mpm_err_clear(&err);
      const int rc = (*t)->check(&par, &err);
      ck_assert_msg(rc == MPM_EINPUT && err.code == MPM_EINPUT,
                    "%s: material.%s = NaN: status %d (code %d), want MPM_EINPUT",
                    (*t)->name, *k, rc, err.code);
      ck_assert_msg(names_key(err.msg, *k), "%s: material.%s = NaN: message '%s'",
                    (*t)->name, *k, err.msg);
    }
  }
}
END_TEST

/* ------------------------------------------- 5. the batch is the point update */

/* xorshift64* generator; state passed by the caller. */
static double rnd(unsigned long long *st)
{
  *st ^= *st >> 12;
  *st ^= *st << 25;
  *st ^= *st >> 27;
  return (double)((*st * 0x2545F4914F6CDD1DULL) >> 11) * 0x1.0p-53;
}

enum { NB = 37 };   /* not a multiple of a vector's width: a remainder too */

/* One batch of NB random points of dimension dim through model t's update
 * (steady: its steady form), nsub substeps, against update_point (or
 * update_steady_point) point by point; 1 when every output is bitwise the
 * same. */
static int batch_is_point(const mpm_material_type *t, int steady, int dim, unsigned long long seed)
{
  const mpm_material_params par = table1(1e6, MPM_NGF_DK);
  const int nsub = 3;
  const double dt = 2e-4;
  double L[9][NB], rho[NB], lap[NB], isp[NB], sig[6][NB], g[NB], gdp[NB], F[9][NB], Fp[9][NB];
  int state[NB];
  mpm_mpoint pt[NB];
  mpm_mdeform def[NB];
  mpm_mat3 Lm[NB];
  for (int q = 0; q < NB; q++) {
    mpm_mat3 l = {{{0.0}}};
    for (int i = 0; i < dim; i++)
      for (int j = 0; j < dim; j++)
        l.m[i][j] = (rnd(&seed) - 0.5) * 40.0;               /* |L| ~ 20 1/s */
    const double p = P0 * (q % 5 == 4 ? -0.1 : rnd(&seed) + 0.2);  /* some in tension */
    mpm_sym3 s = {-p + 100.0 * (rnd(&seed) - 0.5), -p + 100.0 * (rnd(&seed) - 0.5),
                  -p + 100.0 * (rnd(&seed) - 0.5), 300.0 * (rnd(&seed) - 0.5),
                  dim == 3 ? 300.0 * (rnd(&seed) - 0.5) : 0.0,
                  dim == 3 ? 300.0 * (rnd(&seed) - 0.5) : 0.0};
    mpm_mat3 f = {{{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}}};
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++)
        if (dim == 3 || (i < 2 && j < 2) || i == j)     /* plane strain: no out-of-plane shear */
          f.m[i][j] -= (i == j ? 3e-3 : 1e-3) * rnd(&seed);  /* a compressed F */
    pt[q] = (mpm_mpoint){.sigma = s, .rho = q % 7 == 3 ? RHO_L : RHO_D, .g = 5.0 * rnd(&seed),
                         .lap = 1e3 * (rnd(&seed) - 0.5), .isp = 0.03 * rnd(&seed),
                         .gdp = 0.0, .state = MPM_STATE_DENSE};
    def[q] = (mpm_mdeform){.F = f, .Fp = {{{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}}}};
    Lm[q] = l;
    for (int i = 0; i < dim; i++)
      for (int j = 0; j < dim; j++)
        L[dim * i + j][q] = l.m[i][j];
    rho[q] = pt[q].rho;
    lap[q] = pt[q].lap;
    isp[q] = pt[q].isp;
    const double sv[6] = {s.xx, s.yy, s.zz, s.xy, s.yz, s.zx};
    for (int k = 0; k < 6; k++)
      sig[k][q] = sv[k];
    g[q] = pt[q].g;
    gdp[q] = pt[q].gdp;
    state[q] = pt[q].state;
    for (int e = 0; e < 9; e++) {
      F[e][q] = def[q].F.m[e / 3][e % 3];
      Fp[e][q] = def[q].Fp.m[e / 3][e % 3];
    }
  }
  mpm_material_batch b = {.n = NB, .dim = dim, .rho = rho, .lap = t->nonlocal ? lap : NULL,
                          .isp = t->nonlocal ? isp : NULL, .g = g, .gdp = gdp, .state = state};
  for (int k = 0; k < dim * dim; k++)
    b.L[k] = L[k];
  for (int k = 0; k < (dim == 3 ? 6 : 4); k++)
    b.sig[k] = sig[k];
  for (int e = 0; t->defgrad && e < 9; e++) {
    b.F[e] = F[e];
    b.Fp[e] = Fp[e];
  }
  (steady ? t->update_steady : t->update)(&par, dt, nsub, &b);
  int same = 1;
  for (int q = 0; q < NB; q++) {
    if (!t->nonlocal)
      pt[q].lap = pt[q].isp = 0.0;
    for (int k = 0; k < nsub; k++)
      (steady ? t->update_steady_point : t->update_point)(&par, &Lm[q], dt, &pt[q], &def[q]);
    const double sv[6] = {pt[q].sigma.xx, pt[q].sigma.yy, pt[q].sigma.zz, pt[q].sigma.xy,
                          pt[q].sigma.yz, pt[q].sigma.zx};
    for (int k = 0; k < (dim == 3 ? 6 : 4); k++)
      same &= !memcmp(&sv[k], &sig[k][q], sizeof(double));
    same &= !memcmp(&pt[q].g, &g[q], sizeof(double)) && !memcmp(&pt[q].gdp, &gdp[q], sizeof(double));
    same &= pt[q].state == state[q];
    for (int e = 0; t->defgrad && e < 9; e++)
      same &= !memcmp(&def[q].F.m[e / 3][e % 3], &F[e][q], sizeof(double)) &&
              !memcmp(&def[q].Fp.m[e / 3][e % 3], &Fp[e][q], sizeof(double));
  }
  return same;
}

START_TEST(t_batch_is_point)
{
  int checked = 0;
  for (const mpm_material_type *const *t = mpm_material_table; *t; t++)
    for (int steady = 0; steady < 1 + ((*t)->update_steady != NULL); steady++)
      for (int dim = 2; dim <= 3; dim++) {
        ck_assert_msg(batch_is_point(*t, steady, dim, 0x9E3779B97F4A7C15ULL + (unsigned)dim),
                      "model %s%s, %dD: the batch update differs from the point update",
                      (*t)->name, steady ? "/steady" : "", dim);
        checked++;
      }
  ck_assert_int_ge(checked, 8);                /* 4 models in 2 dimensions, and steady forms */
}
END_TEST

/* ------------------------------------------------------- registry */

START_TEST(t_registry)
{
  int n = 0;
  for (const mpm_material_type *const *t = mpm_material_table; *t; t++, n++) {
    ck_assert_ptr_nonnull((*t)->name);
    ck_assert_ptr_nonnull((*t)->description);
    /* every model has both updates; a steady form, both of its own */
    ck_assert_ptr_nonnull((*t)->update);
    ck_assert_ptr_nonnull((*t)->update_point);
    ck_assert_int_eq((*t)->update_steady == NULL, (*t)->update_steady_point == NULL);
    ck_assert_ptr_eq(mpm_material_lookup((*t)->name), *t);  /* names unique */
  }
  ck_assert_int_ge(n, 1);
  for (size_t i = 0; i < sizeof used_keys / sizeof used_keys[0]; i++)
    ck_assert_msg(mpm_material_lookup(used_keys[i].model) != NULL,
                  "key list for '%s', which is not in the table", used_keys[i].model);
  ck_assert_ptr_null(mpm_material_lookup("no such model"));
}
END_TEST

int main(void)
{
  Suite *s = suite_create("material");
  TCase *tc = tcase_create("material");
  tcase_set_timeout(tc, 60);
  tcase_add_test(tc, t_registry);
  tcase_add_test(tc, t_cases_as_stated);
  tcase_add_test(tc, t_frame_indifference);
  tcase_add_test(tc, t_zero_stays_zero);
  tcase_add_test(tc, t_elastic_step);
  tcase_add_test(tc, t_check_rejects_nan);
  tcase_add_test(tc, t_batch_is_point);
  suite_add_tcase(s, tc);
  SRunner *sr = srunner_create(s);
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf ? EXIT_FAILURE : EXIT_SUCCESS;
}
