/* test_mu_i.c: the trans-phase mu(I) update (MODEL.md section 4), tested from
 * its equations: elastic below yield, the return relations, steady simple
 * shear, rigid rotation of the loading, disconnection, and the limits
 * p -> 0+, tau_tr -> 0 and mu -> mu_2. */
#include <check.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/points.h"
#include "core/tensor3.h"
#include "material/material.h"

/* [DK15] App. B material: Table 1 with E = 1e4 Pa (G = 3846 Pa, K = 8333 Pa). */
static mpm_material_params dk15_params(double E)
{
  mpm_material_params par = {.E = E, .nu = 0.3, .rho_s = 2450.0, .rho_c = 1500.0,
                             .mu_s = 0.3819, .mu_2 = 0.6435, .I0 = 0.279, .d = 0.005};
  mpm_material_params_derive(&par);
  return par;
}

static mpm_mat3 plane_L(double xx, double xy, double yx, double yy)
{
  return (mpm_mat3){{{xx, xy, 0.0}, {yx, yy, 0.0}, {0.0, 0.0, 0.0}}};
}

/* -p I plus an in-plane deviator (a, -a, 0; c) and sigma_zz offset z. */
static mpm_sym3 stress(double p, double a, double c, double z)
{
  return (mpm_sym3){-p + a, -p - a, -p + z, c, 0.0, 0.0};
}

static mpm_mpoint point(mpm_sym3 s, double rho)
{
  return (mpm_mpoint){.sigma = s, .rho = rho};
}

/* mu(I) = mu_s + dmu / (I0/I + 1), I = gdot_p d sqrt(rho_s / p) */
static double mu_of_rate(const mpm_material_params *par, double gdp, double p)
{
  double I = gdp * par->d * sqrt(par->rho_s / p);
  return I > 0.0 ? par->mu_s + par->dmu / (par->I0 / I + 1.0) : par->mu_s;
}

static int sym3_finite(mpm_sym3 s)
{
  return isfinite(s.xx) && isfinite(s.yy) && isfinite(s.zz) && isfinite(s.xy) &&
         isfinite(s.yz) && isfinite(s.zx);
}

static double sym3_maxabs(mpm_sym3 s)
{
  double v[6] = {s.xx, s.yy, s.zz, s.xy, s.yz, s.zx}, m = 0.0;
  for (int i = 0; i < 6; i++)
    m = fabs(v[i]) > m ? fabs(v[i]) : m;
  return m;
}

/* Trial stress of MODEL.md section 4 step 2, for checks. */
static mpm_sym3 trial(const mpm_material_params *par, mpm_mat3 L, double dt, mpm_sym3 s)
{
  mpm_mat3 W = mpm_mat3_skw(&L);
  return mpm_sym3_axpy(s, dt, mpm_sym3_add(mpm_sym3_elastic(mpm_mat3_sym(&L), par->G, par->K),
                                           mpm_sym3_spin(&W, s)));
}

/* Deterministic pseudo-random numbers in [0, 1) (no global state). */
static double lcg(unsigned long *s)
{
  *s = *s * 6364136223846793005UL + 1442695040888963407UL;
  return (double)(*s >> 11) / 9007199254740992.0;
}

/* ------------------------------------------------------------------ */

/* Below yield (tau_tr <= mu_s p_tr) the update is the elastic Jaumann update. */
START_TEST(t_elastic_below_yield)
{
  mpm_material_params par = dk15_params(1e4);
  unsigned long seed = 1;
  int checked = 0;
  for (int i = 0; i < 200; i++) {
    double p = 100.0 + 1000.0 * lcg(&seed), mu = 0.3 * lcg(&seed), ang = 6.3 * lcg(&seed);
    mpm_sym3 s = stress(p, mu * p * cos(ang), mu * p * sin(ang), 0.1 * p * (lcg(&seed) - 0.5));
    mpm_mat3 L = plane_L(0.1 * (lcg(&seed) - 0.5), 0.1 * (lcg(&seed) - 0.5),
                         0.1 * (lcg(&seed) - 0.5), 0.1 * (lcg(&seed) - 0.5));
    double dt = 1e-3;
    mpm_sym3 st = trial(&par, L, dt, s);
    if (!(mpm_sym3_tau(st) <= par.mu_s * mpm_sym3_pressure(st)))
      continue;  /* only cases below yield */
    mpm_mpoint a = point(s, 1600.0), b = point(s, 1600.0);
    mpm_material_mu_i.update_point(&par, &L, dt, &a, NULL);
    mpm_material_elastic.update_point(&par, &L, dt, &b, NULL);
    /* Same operations in the same order: equal to the last bit; 1e-15 relative
     * allows for a compiler contracting differently in the two files. */
    double tol = 1e-15 * sym3_maxabs(b.sigma);
    ck_assert_double_eq_tol(a.sigma.xx, b.sigma.xx, tol);
    ck_assert_double_eq_tol(a.sigma.yy, b.sigma.yy, tol);
    ck_assert_double_eq_tol(a.sigma.zz, b.sigma.zz, tol);
    ck_assert_double_eq_tol(a.sigma.xy, b.sigma.xy, tol);
    ck_assert_double_eq(a.gdp, 0.0);
    ck_assert_int_eq(a.state, MPM_STATE_DENSE);
    checked++;
  }
  ck_assert_int_gt(checked, 100);
}
END_TEST

/* Above yield: p = p_tr, sigma0 parallel to sigma0_tr, tau = tau_tr - G dt gdot_p,
 * tau/p = mu(I(gdot_p)), tau solves tau^2 - B tau + H = 0 (MODEL.md section 4). */
START_TEST(t_return_relations)
{
  unsigned long seed = 7;
  int checked = 0;
  for (int i = 0; i < 2000; i++) {
    mpm_material_params par = dk15_params(i % 2 ? 1e4 : 1e8);
    double p = pow(10.0, 4.0 * lcg(&seed)), mu = 1.2 * lcg(&seed), ang = 6.3 * lcg(&seed);
    mpm_sym3 s = stress(p, mu * p * cos(ang), mu * p * sin(ang), 0.2 * p * (lcg(&seed) - 0.5));
    double g = pow(10.0, 4.0 * lcg(&seed) - 3.0);
    mpm_mat3 L = plane_L(g * (lcg(&seed) - 0.5), g * (lcg(&seed) - 0.5),
                         g * (lcg(&seed) - 0.5), g * (lcg(&seed) - 0.5));
    double dt = pow(10.0, -2.0 - 4.0 * lcg(&seed));
    mpm_sym3 st = trial(&par, L, dt, s);
    double p_tr = mpm_sym3_pressure(st), tau_tr = mpm_sym3_tau(st);
    if (!(p_tr > 0.0) || tau_tr <= par.mu_s * p_tr)
      continue;  /* only plastic cases */
    mpm_mpoint pt = point(s, 1600.0);
    mpm_material_mu_i.update_point(&par, &L, dt, &pt, NULL);
    double p1 = mpm_sym3_pressure(pt.sigma), tau1 = mpm_sym3_tau(pt.sigma);
    ck_assert_int_eq(pt.state, MPM_STATE_DENSE);
    ck_assert(pt.gdp > 0.0 && isfinite(pt.gdp));
    /* p unchanged by the return: scaling a deviator keeps the trace up to
     * round-off of the deviator's entries. */
    ck_assert_double_eq_tol(p1, p_tr, 1e-14 * (p_tr + tau_tr));
    /* tau = tau_tr - G dt gdot_p: gdot_p was formed from that difference, so
     * they agree to a few roundings of tau_tr. */
    ck_assert_double_eq_tol(tau1, tau_tr - par.G * dt * pt.gdp, 1e-14 * tau_tr);
    /* mu_s < mu < mu_2 (the small root lies in (S0, min(S2, tau_tr))) */
    ck_assert(tau1 > par.mu_s * p_tr * (1.0 - 1e-14) && tau1 < par.mu_2 * p_tr);
    /* the mu(I) law at the returned rate: the forward map I -> mu is well
     * conditioned (|dmu/dI| I <= dmu / 4), so only gdot_p's own relative
     * round-off, at most eps tau_tr / (tau_tr - tau), shows. */
    double rel = 4.0 * 2.2e-16 * tau_tr / (tau_tr - tau1);
    ck_assert_double_eq_tol(tau1 / p1, mu_of_rate(&par, pt.gdp, p1), 1e-12 + par.dmu * rel);
    /* quadratic residual relative to its terms */
    double S0 = par.mu_s * p_tr, S2 = par.mu_2 * p_tr;
    double alpha = par.xi * par.G * dt * sqrt(p_tr);
    double B = S2 + tau_tr + alpha, H = S2 * tau_tr + S0 * alpha;
    ck_assert_double_le(fabs(tau1 * tau1 - B * tau1 + H), 1e-13 * B * B);
    /* codirectional deviators: sigma0 = (tau/tau_tr) sigma0_tr */
    mpm_sym3 d1 = mpm_sym3_dev(pt.sigma), d0 = mpm_sym3_dev(st);
    double r = tau1 / tau_tr;
    ck_assert_double_eq_tol(d1.xy, r * d0.xy, 1e-13 * tau_tr);
    ck_assert_double_eq_tol(d1.xx, r * d0.xx, 1e-13 * tau_tr);
    ck_assert_double_eq_tol(d1.zz, r * d0.zz, 1e-13 * tau_tr);
    checked++;
  }
  ck_assert_int_gt(checked, 500);
}
END_TEST

/* Steady simple shear L = gdot e_x (x) e_y under -p0 I. At a fixed point of the
 * update, sigma_tr - sigma = G dt gdot_p sigma0 / tau, i.e.
 *   2G D0 + W s0 - s0 W = 2G Dp:
 * the continuous steady state itself, for any dt. Contracting with s0 gives
 * gdot_p tau = D0:s0 = gdot sxy, so gdot_p = gdot cos(theta), theta the angle by
 * which the spin turns s0 away from D0 (tan theta = gdot tau / (G gdot_p), about
 * tau / G). We compare mu = tau/p with mu(I) at the imposed rate gdot; they
 * differ by at most dmu (1 - cos theta) ~ dmu (tau/G)^2 / 2. */
static mpm_mpoint steady_shear(const mpm_material_params *par, double gdot, double p0,
                               double dt, long nsteps, double *last_change)
{
  mpm_mat3 L = plane_L(0.0, gdot, 0.0, 0.0);
  mpm_mpoint pt = point(stress(p0, 0.0, 0.0, 0.0), 1600.0);
  *last_change = 0.0;
  for (long k = 0; k < nsteps; k++) {
    mpm_sym3 prev = pt.sigma;
    mpm_material_mu_i.update_point(par, &L, dt, &pt, NULL);
    *last_change = sym3_maxabs(mpm_sym3_axpy(pt.sigma, -1.0, prev));
  }
  return pt;
}

START_TEST(t_steady_simple_shear)
{
  mpm_material_params par = dk15_params(1e7);  /* G = 3.8e6 Pa: tau/G ~ 1e-4 */
  const double gdot = 1.0, p0 = 1000.0;
  double change;
  /* yield after tau/(G gdot) ~ 1e-4 s; relaxation rate G dgdot_p/dtau ~ 5e5 1/s;
   * 2e4 steps of 1e-5 s are 0.2 s, thousands of relaxation times. */
  mpm_mpoint a = steady_shear(&par, gdot, p0, 1e-5, 20000, &change);
  double p = mpm_sym3_pressure(a.sigma), tau = mpm_sym3_tau(a.sigma);
  ck_assert_double_le(change, 1e-12 * p0);                    /* stationary */
  ck_assert_double_eq_tol(p, p0, 1e-12 * p0);                  /* tr D = 0 */
  ck_assert_double_eq_tol(a.gdp * tau, gdot * a.sigma.xy, 1e-10 * gdot * tau);
  double cos_theta = a.sigma.xy / tau;
  ck_assert_double_le(1.0 - cos_theta, 1e-7);                  /* ~ (tau/G)^2 / 2 */
  ck_assert_double_eq_tol(tau / p, mu_of_rate(&par, a.gdp, p), 1e-12);
  ck_assert_double_eq_tol(tau / p, mu_of_rate(&par, gdot, p), par.dmu * (1.0 - cos_theta) + 1e-12);
  /* well above mu_s: the point flows */
  ck_assert_double_gt(tau / p, par.mu_s + 0.005);
  /* the fixed point does not depend on dt */
  mpm_mpoint b = steady_shear(&par, gdot, p0, 1e-4, 4000, &change);
  ck_assert_double_eq_tol(b.sigma.xy, a.sigma.xy, 1e-9 * tau);
  ck_assert_double_eq_tol(b.sigma.xx, a.sigma.xx, 1e-9 * tau);
  ck_assert_double_eq_tol(b.gdp, a.gdp, 1e-9 * gdot);
}
END_TEST

/* R (.) R^T about z by angle a. */
static mpm_mat3 rot_mat(mpm_mat3 A, double a)
{
  double c = cos(a), s = sin(a);
  mpm_mat3 R = {{{c, -s, 0}, {s, c, 0}, {0, 0, 1}}}, T, out;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      T.m[i][j] = 0.0;
      for (int k = 0; k < 3; k++)
        T.m[i][j] += R.m[i][k] * A.m[k][j];
    }
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++) {
      out.m[i][j] = 0.0;
      for (int k = 0; k < 3; k++)
        out.m[i][j] += T.m[i][k] * R.m[j][k];
    }
  return out;
}

static mpm_sym3 rot_sym(mpm_sym3 s, double a)
{
  mpm_mat3 r = rot_mat(mpm_sym3_full(s), a);
  return (mpm_sym3){r.m[0][0], r.m[1][1], r.m[2][2], 0.5 * (r.m[0][1] + r.m[1][0]), 0.0, 0.0};
}

/* A loading that compresses, shears and extends, so the point goes elastic ->
 * plastic -> disconnected (p_tr <= 0) -> dense again. */
static mpm_mat3 wild_L(double t)
{
  return plane_L(0.3 * sin(3.0 * t), 0.3 + 0.2 * sin(5.0 * t), -0.1 * cos(2.0 * t),
                 0.3 * sin(3.0 * t) - 0.05 * cos(t));
}

/* Rotating the whole history rigidly (R L R^T, R sigma0 R^T) leaves the
 * invariants p, tau and gdot_p unchanged: the update is objective. */
START_TEST(t_rotation_invariance)
{
  mpm_material_params par = dk15_params(1e4);
  const double dt = 2e-3, ang = 0.7;
  mpm_sym3 s0 = stress(500.0, 40.0, 90.0, -20.0);
  mpm_mpoint a = point(s0, 1700.0), b = point(rot_sym(s0, ang), 1700.0);
  int states[2] = {0, 0};
  for (int k = 0; k < 1500; k++) {
    mpm_mat3 L = wild_L(k * dt), Lr = rot_mat(L, ang);
    double rho = a.rho * exp(-dt * mpm_mat3_trace(&L));       /* tr L is invariant */
    a.rho = b.rho = rho;
    mpm_material_mu_i.update_point(&par, &L, dt, &a, NULL);
    mpm_material_mu_i.update_point(&par, &Lr, dt, &b, NULL);
    ck_assert_int_eq(a.state, b.state);
    states[a.state]++;
    /* round-off of the rotation (~1e-16 relative) carried through the steps;
     * 1e-9 of the stress scale is far above it and far below any real effect */
    double scale = 1e-9 * (fabs(mpm_sym3_pressure(a.sigma)) + 1.0);
    ck_assert_double_eq_tol(mpm_sym3_pressure(b.sigma), mpm_sym3_pressure(a.sigma), scale);
    ck_assert_double_eq_tol(mpm_sym3_tau(b.sigma), mpm_sym3_tau(a.sigma), scale);
    ck_assert_double_eq_tol(b.gdp, a.gdp, 1e-9 * (a.gdp + 1.0));
  }
  /* the history visits both states */
  ck_assert_int_gt(states[MPM_STATE_DENSE], 100);
  ck_assert_int_gt(states[MPM_STATE_DISCONNECTED], 10);
}
END_TEST

/* Disconnected (rho < rho_c, or p_tr <= 0): zero stress, gdot_p = sqrt(2 D0:D0). */
START_TEST(t_disconnected_zero_stress)
{
  mpm_material_params par = dk15_params(1e4);
  mpm_mat3 L = plane_L(0.2, 0.5, -0.1, 0.3);
  mpm_sym3 D0 = mpm_sym3_dev(mpm_mat3_sym(&L));
  double d0 = sqrt(2.0 * mpm_sym3_ddot(D0, D0));
  struct { mpm_sym3 s; double rho; } cases[] = {
    {stress(1000.0, 100.0, 50.0, 0.0), 1499.999},   /* rho < rho_c under pressure */
    {stress(-10.0, 1.0, 2.0, 0.0), 1600.0},         /* tension: p_tr < 0 */
    {stress(1e-3, 0.0, 0.0, 0.0), 1600.0},          /* extension removes the last 1e-3 Pa */
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    mpm_mpoint pt = point(cases[i].s, cases[i].rho);
    pt.gdp = 123.0;
    mpm_material_mu_i.update_point(&par, &L, 1e-3, &pt, NULL);
    ck_assert_int_eq(pt.state, MPM_STATE_DISCONNECTED);
    ck_assert_double_eq(sym3_maxabs(pt.sigma), 0.0);
    ck_assert_double_eq_tol(pt.gdp, d0, 1e-15 * d0);
  }
  /* p_tr = 0 exactly: stress-free under pure shear stays stress-free */
  mpm_mat3 S = plane_L(0.0, 0.05, 0.0, 0.0);
  mpm_mpoint pt = point(mpm_sym3_zero(), 1500.0);
  for (int k = 0; k < 10; k++) {
    mpm_material_mu_i.update_point(&par, &S, 1e-3, &pt, NULL);
    ck_assert_int_eq(pt.state, MPM_STATE_DISCONNECTED);
    ck_assert_double_eq(sym3_maxabs(pt.sigma), 0.0);
    ck_assert_double_eq_tol(pt.gdp, 0.05, 1e-16);
  }
  /* rho = rho_c exactly with compression: dense (the rule is rho < rho_c) */
  mpm_mat3 C = plane_L(-0.1, 0.05, 0.0, -0.1);
  mpm_material_mu_i.update_point(&par, &C, 1e-3, &pt, NULL);
  ck_assert_int_eq(pt.state, MPM_STATE_DENSE);
  ck_assert_double_gt(mpm_sym3_pressure(pt.sigma), 0.0);
}
END_TEST

static void assert_sane(const mpm_material_params *par, const mpm_mpoint *pt, double p_tr)
{
  ck_assert(sym3_finite(pt->sigma));
  ck_assert(isfinite(pt->gdp) && pt->gdp >= 0.0);
  ck_assert_int_eq(pt->state, MPM_STATE_DENSE);
  double tau = mpm_sym3_tau(pt->sigma);
  ck_assert_double_le(tau, par->mu_2 * p_tr * (1.0 + 1e-12));
}

/* p -> 0+: sheared at tiny pressure, the point returns tau <= mu_2 p and turns
 * nearly all of the shear into plastic flow: gdot_p -> sqrt(2 D0:D0) = gdot. */
START_TEST(t_limit_p_to_zero)
{
  mpm_material_params par = dk15_params(1e4);
  const double gdot = 1.0, dt = 1e-3;
  mpm_mat3 L = plane_L(0.0, gdot, 0.0, 0.0);
  const double ps[] = {1e-3, 1e-12, 1e-30, 1e-200, 1e-300, 4.9e-324};
  for (size_t i = 0; i < sizeof ps / sizeof ps[0]; i++) {
    mpm_mpoint pt = point(stress(ps[i], 0.0, 0.0, 0.0), 1600.0);
    mpm_material_mu_i.update_point(&par, &L, dt, &pt, NULL);
    double p_tr = ps[i];
    assert_sane(&par, &pt, p_tr);
    /* gdot_p = gdot - tau/(G dt), tau <= mu_2 p: within mu_2 p / (G dt) of gdot */
    ck_assert_double_eq_tol(pt.gdp, gdot, 1e-12 + par.mu_2 * p_tr / (par.G * dt));
  }
  /* tau_tr tiny as well: a deviator at mu = 1 of a tiny pressure, no loading */
  mpm_mat3 Z = plane_L(0, 0, 0, 0);
  for (size_t i = 0; i < sizeof ps / sizeof ps[0]; i++) {
    mpm_mpoint pt = point(stress(ps[i], 0.0, ps[i], 0.0), 1600.0);
    if (!(mpm_sym3_pressure(pt.sigma) > 0.0))
      continue;  /* the subnormal pressure is lost in -p + 0 rounding */
    mpm_material_mu_i.update_point(&par, &Z, dt, &pt, NULL);
    assert_sane(&par, &pt, ps[i]);
    /* below ~1e-154 Pa the squares in tau = sqrt(s0:s0/2) underflow, tau reads 0
     * and the point stays elastic: finite, but the lower bound is not tested */
    if (ps[i] >= 1e-150)
      ck_assert_double_ge(mpm_sym3_tau(pt.sigma), par.mu_s * ps[i] * (1.0 - 1e-12));
  }
}
END_TEST

/* tau_tr -> 0: no division by tau_tr. */
START_TEST(t_limit_tau_to_zero)
{
  mpm_material_params par = dk15_params(1e4);
  mpm_mat3 Z = plane_L(0, 0, 0, 0);
  /* tau_tr = 0 exactly: elastic branch, stress unchanged */
  mpm_mpoint pt = point(stress(1000.0, 0.0, 0.0, 0.0), 1600.0);
  mpm_material_mu_i.update_point(&par, &Z, 1e-3, &pt, NULL);
  ck_assert_double_eq(pt.sigma.xx, -1000.0);
  ck_assert_double_eq(pt.sigma.xy, 0.0);
  ck_assert_double_eq(pt.gdp, 0.0);
  /* mu_s = 0: S0 = 0, so any tau_tr > 0 is plastic, down to subnormal tau_tr */
  par.mu_s = 0.0;
  mpm_material_params_derive(&par);
  const double taus[] = {1e-3, 1e-100, 1e-300, 4.9e-324, 0.0};
  for (size_t i = 0; i < sizeof taus / sizeof taus[0]; i++) {
    mpm_mpoint q = point(stress(1000.0, 0.0, taus[i], 0.0), 1600.0);
    mpm_material_mu_i.update_point(&par, &Z, 1e-3, &q, NULL);
    assert_sane(&par, &q, 1000.0);
    ck_assert_double_le(mpm_sym3_tau(q.sigma), taus[i]);
  }
}
END_TEST

/* mu -> mu_2: very fast shear drives tau to S2 from below; and the case
 * tau_tr ~ S2 with tiny alpha, where B^2 - 4H would cancel. */
START_TEST(t_limit_mu_to_mu2)
{
  mpm_material_params par = dk15_params(1e4);
  const double p = 1000.0, gdots[] = {1e2, 1e4, 1e8, 1e12};
  for (size_t i = 0; i < sizeof gdots / sizeof gdots[0]; i++) {
    mpm_mat3 L = plane_L(0.0, gdots[i], 0.0, 0.0);
    mpm_mpoint pt = point(stress(p, 0.0, 0.0, 0.0), 1600.0);
    mpm_material_mu_i.update_point(&par, &L, 1e-3, &pt, NULL);
    assert_sane(&par, &pt, p);
    double mu = mpm_sym3_tau(pt.sigma) / p;
    ck_assert_double_lt(mu, par.mu_2);
    ck_assert_double_gt(mu, par.mu_s);
    ck_assert_double_eq_tol(mu, mu_of_rate(&par, pt.gdp, p), 1e-12);
  }
  /* tau_tr = S2 (1 + 1e-12) and alpha tiny (dt = 1e-14 with L = 0) */
  const double dts[] = {1e-6, 1e-10, 1e-14, 1e-20};
  mpm_mat3 Z = plane_L(0, 0, 0, 0);
  for (size_t i = 0; i < sizeof dts / sizeof dts[0]; i++) {
    double c = par.mu_2 * p * (1.0 + 1e-12);
    mpm_mpoint pt = point(stress(p, 0.0, c, 0.0), 1600.0);
    mpm_material_mu_i.update_point(&par, &Z, dts[i], &pt, NULL);
    assert_sane(&par, &pt, p);
    double tau = mpm_sym3_tau(pt.sigma);
    /* small root in (S0, min(S2, tau_tr)) */
    ck_assert_double_le(tau, par.mu_2 * p);
    ck_assert_double_gt(tau, par.mu_s * p);
  }
}
END_TEST

/* gdot_p from a stress inverts mu(I): mu(I(gdot_p)) = tau / p between mu_s and
 * mu_2; 0 at or below mu_s and for p <= 0, +inf from mu_2 on; sqrt(2 D0:D0)
 * for a disconnected point whatever its stress. */
START_TEST(t_gdp_of_stress)
{
  mpm_material_params par = dk15_params(1e4);
  mpm_sym3 D = {0.3, -0.1, 0.0, 0.2, 0.0, 0.0};
  double p = 250.0;
  for (int i = 1; i < 20; i++) {
    double mu = par.mu_s + par.dmu * i / 20.0;
    double gdp = mpm_material_mu_i_gdp(&par, stress(p, 0.0, mu * p, 0.0), D, MPM_STATE_DENSE);
    ck_assert(gdp > 0.0 && isfinite(gdp));
    ck_assert_double_eq_tol(mu_of_rate(&par, gdp, p), mu, 1e-13);
  }
  ck_assert_double_eq(mpm_material_mu_i_gdp(&par, stress(p, 0.0, par.mu_s * p, 0.0), D,
                                            MPM_STATE_DENSE), 0.0);
  ck_assert(isinf(mpm_material_mu_i_gdp(&par, stress(p, 0.0, par.mu_2 * p, 0.0), D,
                                        MPM_STATE_DENSE)));
  ck_assert_double_eq(mpm_material_mu_i_gdp(&par, stress(-1.0, 0.0, 1.0, 0.0), D,
                                            MPM_STATE_DENSE), 0.0);
  mpm_sym3 D0 = mpm_sym3_dev(D);
  ck_assert_double_eq(mpm_material_mu_i_gdp(&par, stress(p, 0.0, par.mu_2 * p, 0.0), D,
                                            MPM_STATE_DISCONNECTED),
                      sqrt(2.0 * mpm_sym3_ddot(D0, D0)));
}
END_TEST

/* The parameter check names the key that is out of range. */
START_TEST(t_check_params)
{
  mpm_material_params ok = dk15_params(1e4);
  mpm_err err = {0};
  ck_assert_int_eq(mpm_material_mu_i.check(&ok, &err), MPM_OK);
  struct { const char *key; mpm_material_params par; } bad[] = {
    {"material.mu_2", ok}, {"material.d", ok}, {"material.I0", ok},
    {"material.rho_c", ok}, {"material.E", ok}, {"material.mu_s", ok},
  };
  bad[0].par.mu_2 = ok.mu_s;
  bad[1].par.d = 0.0;
  bad[2].par.I0 = -1.0;
  bad[3].par.rho_c = 3000.0;
  bad[4].par.E = 0.0;
  bad[5].par.mu_s = -0.1;
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    mpm_err e = {0};
    ck_assert_int_eq(mpm_material_mu_i.check(&bad[i].par, &e), MPM_EINPUT);
    ck_assert_msg(strstr(e.msg, bad[i].key) != NULL, "'%s' does not name %s", e.msg,
                  bad[i].key);
  }
  ck_assert_ptr_eq(mpm_material_lookup("mu_i"), &mpm_material_mu_i);
}
END_TEST

int main(void)
{
  Suite *s = suite_create("mu_i");
  TCase *tc = tcase_create("mu_i");
  tcase_set_timeout(tc, 60);
  tcase_add_test(tc, t_elastic_below_yield);
  tcase_add_test(tc, t_return_relations);
  tcase_add_test(tc, t_steady_simple_shear);
  tcase_add_test(tc, t_rotation_invariance);
  tcase_add_test(tc, t_disconnected_zero_stress);
  tcase_add_test(tc, t_limit_p_to_zero);
  tcase_add_test(tc, t_limit_tau_to_zero);
  tcase_add_test(tc, t_limit_mu_to_mu2);
  tcase_add_test(tc, t_gdp_of_stress);
  tcase_add_test(tc, t_check_params);
  suite_add_tcase(s, tc);
  SRunner *sr = srunner_create(s);
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf ? EXIT_FAILURE : EXIT_SUCCESS;
}
