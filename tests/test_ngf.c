/* test_ngf.c: the per-point NGF update (MODEL.md section 5 steps 3-5), tested
 * from its equations: the chosen root solves the quadratic and the split update
 * to round-off and is the physical one; the flow rule; A = 0 steady simple
 * shear gives mu(I) ([DK-silo] form) or mu_s + b I ([HS21] form); g >= 0;
 * disconnection and reconsolidation; seeding; limits; parameter checks. */
#include <check.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/points.h"
#include "core/tensor3.h"
#include "material/material.h"

/* [DK15] Table 1 granular values with [DK-silo] A and t0. */
static mpm_material_params ngf_params(double E, int form)
{
  mpm_material_params par = {.E = E, .nu = 0.3, .rho_s = 2450.0, .rho_c = 1500.0,
                             .mu_s = 0.3819, .mu_2 = 0.6435, .I0 = 0.279, .d = 0.005,
                             .A = 0.48, .t0 = 1e-3, .form = form};
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

static mpm_mpoint point(mpm_sym3 s, double rho, double g, double lap)
{
  return (mpm_mpoint){.sigma = s, .rho = rho, .g = g, .lap = lap};
}

/* Trial stress of MODEL.md section 4 step 2, computed here independently. */
static mpm_sym3 trial(const mpm_material_params *par, mpm_mat3 L, double dt, mpm_sym3 s)
{
  mpm_mat3 W = mpm_mat3_skw(&L);
  return mpm_sym3_axpy(s, dt, mpm_sym3_add(mpm_sym3_elastic(mpm_mat3_sym(&L), par->G, par->K),
                                           mpm_sym3_spin(&W, s)));
}

static double sym3_maxabs(mpm_sym3 s)
{
  double v[6] = {s.xx, s.yy, s.zz, s.xy, s.yz, s.zx}, m = 0.0;
  for (int i = 0; i < 6; i++)
    m = fabs(v[i]) > m ? fabs(v[i]) : m;
  return m;
}

/* Deterministic pseudo-random numbers in [0, 1) (no global state). */
static double lcg(unsigned long *s)
{
  *s = *s * 6364136223846793005UL + 1442695040888963407UL;
  return (double)(*s >> 11) / 9007199254740992.0;
}

/* Log-uniform in [lo, hi]. */
static double logu(unsigned long *s, double lo, double hi)
{
  return lo * pow(hi / lo, lcg(s));
}

/* Quadratic of MODEL.md section 5 step 4, in long double from the definitions:
 * q[0..2] = a, b', c'; *scale = |a| x^2 + B x + C with B, C the sums of the
 * magnitudes of the elementary products in b' and c' (tau_tr and S2 counted
 * apart: the code forms S2 = mu_2 p and tau_tr - S2 in double, so near
 * tau_tr = S2 that difference is only known to eps S2). A backward-stable root
 * has a residual of a few eps times this scale. */
static void quad_ref(const mpm_material_params *par, double dt, double p, double tau_tr,
                     double gs, double mug_n, double x, long double q[3], long double *scale)
{
  long double k = (long double)dt / par->t0, Gb = (long double)par->G * dt;
  long double c = k * par->b * par->d * sqrtl((long double)par->rho_s / p) * mug_n;
  long double beta = 1.0L + c, S0 = (long double)par->mu_s * p, S2 = (long double)par->mu_2 * p;
  long double B, C;
  if (par->form == MPM_NGF_HS21) {
    q[0] = Gb * (beta + k * par->mu_s);
    q[1] = beta * p - Gb * gs + k * (S0 - tau_tr);
    q[2] = -(long double)gs * p;
    B = beta * p + Gb * gs + k * (S0 + tau_tr);
    C = (long double)gs * p;
  } else {
    long double f = k * par->dmu;
    q[0] = Gb * (beta * par->mu_2 + f * par->mu_s);
    q[1] = beta * (S2 - tau_tr) - par->mu_2 * Gb * gs + f * (S0 - tau_tr);
    q[2] = gs * (tau_tr - S2);
    B = beta * (S2 + tau_tr) + par->mu_2 * Gb * gs + f * (S0 + tau_tr);
    C = gs * (tau_tr + S2);
  }
  *scale = q[0] * x * x + B * x + C;
}

/* mu(x) = tau_tr / (G dt x + p) */
static double mu_of_x(const mpm_material_params *par, double dt, double p, double tau_tr,
                      double x)
{
  return tau_tr / (par->G * dt * x + p);
}

/* One random case of the root sweep: parameters (mu_2 up to 50), p, tau_tr
 * (a third of the cases within 1e-10 ... 1e-3 of S2), g* (a fifth exactly 0). */
typedef struct root_case { mpm_material_params par; double dt, p, tau_tr, gs, mug; } root_case;

static root_case random_case(unsigned long *s, int form)
{
  root_case r;
  r.par = ngf_params(logu(s, 1e4, 1e9), form);
  r.par.mu_s = 0.05 + 0.6 * lcg(s);
  r.par.mu_2 = r.par.mu_s + logu(s, 1e-3, 50.0);
  r.par.I0 = logu(s, 1e-2, 3.0);
  r.par.t0 = logu(s, 1e-5, 1e-1);
  mpm_material_params_derive(&r.par);
  r.dt = logu(s, 1e-8, 1e-3);
  r.p = logu(s, 1e-3, 1e6);
  double u = lcg(s), S2 = r.par.mu_2 * r.p;
  if (u < 1.0 / 3.0)
    r.tau_tr = S2 * (1.0 + (lcg(s) < 0.5 ? -1.0 : 1.0) * logu(s, 1e-10, 1e-3));
  else
    r.tau_tr = S2 * logu(s, 1e-4, 3.0);
  r.gs = lcg(s) < 0.2 ? 0.0 : logu(s, 1e-6, 1e4);
  r.mug = lcg(s) < 0.2 ? 0.0 : logu(s, 1e-6, 1e4);
  return r;
}

/* ------------------------------------------------------------------ */

/* The returned g_{n+1} solves a x^2 + b' x + c' = 0. Residual bound: the code
 * rounds each elementary product and the root formula a few times, each
 * rounding moving the residual by at most eps times one term; 8 eps of the
 * sum of the term sizes covers that (the largest seen in the sweep is 1.7 eps). */
START_TEST(t_root_solves_quadratic)
{
  for (int form = 0; form < 2; form++) {
    unsigned long seed = 12345u + (unsigned long)form;
    long double worst = 0.0L;
    for (int n = 0; n < 200000; n++) {
      root_case r = random_case(&seed, form);
      double x = mpm_material_ngf_fluidity(&r.par, r.dt, r.p, r.tau_tr, r.gs, r.mug, 0.0);
      ck_assert(isfinite(x) && x >= 0.0);
      long double q[3], scale;
      quad_ref(&r.par, r.dt, r.p, r.tau_tr, r.gs, r.mug, x, q, &scale);
      long double res = (q[0] * x + q[1]) * x + q[2];
      if (r.gs == 0.0 && r.tau_tr < r.par.mu_2 * r.p) {
        ck_assert_double_eq(x, 0.0);                 /* the g = 0 branch */
        continue;
      }
      long double rel = scale > 0.0L ? fabsl(res) / scale : 0.0L;
      worst = rel > worst ? rel : worst;
      ck_assert_msg(rel <= 8.0L * DBL_EPSILON, "form %d case %d: residual %Lg of scale %Lg",
                    form, n, res, scale);
    }
    ck_assert(worst <= 8.0L * DBL_EPSILON);
  }
}
END_TEST

/* The chosen root is the physical one: x >= 0, mu(x) < mu_2 ([DK-silo] form),
 * and the other root of the quadratic (c'/(a x) by Vieta) is negative or has
 * mu >= mu_2. With g* = 0 and tau_tr < S2 the answer is x = 0. */
START_TEST(t_root_is_physical)
{
  int both_positive = 0, near_s2 = 0, gzero_flow = 0;
  for (int form = 0; form < 2; form++) {
    unsigned long seed = 777u + (unsigned long)form;
    for (int n = 0; n < 200000; n++) {
      root_case r = random_case(&seed, form);
      double S2 = r.par.mu_2 * r.p;
      double x = mpm_material_ngf_fluidity(&r.par, r.dt, r.p, r.tau_tr, r.gs, r.mug, 0.0);
      ck_assert(x >= 0.0);
      if (r.gs == 0.0 && r.tau_tr < S2) {
        ck_assert_double_eq(x, 0.0);
        continue;
      }
      near_s2 += fabs(r.tau_tr / S2 - 1.0) < 1e-3;
      double mu = mu_of_x(&r.par, r.dt, r.p, r.tau_tr, x);
      if (form == MPM_NGF_DK)
        ck_assert_msg(mu < r.par.mu_2 || x == 0.0, "case %d: mu(x) = %.17g >= mu_2 = %.17g",
                      n, mu, r.par.mu_2);
      if (r.gs == 0.0) {
        gzero_flow += x > 0.0;
        continue;                                    /* roots 0 and x: 0 has mu = mu_tr */
      }
      long double q[3], scale;
      quad_ref(&r.par, r.dt, r.p, r.tau_tr, r.gs, r.mug, x, q, &scale);
      long double other = q[2] / (q[0] * x);
      if (other >= 0.0L) {
        both_positive++;
        ck_assert(other <= x * (1.0L + 1e-9L));      /* x is the larger root */
        double mu_o = mu_of_x(&r.par, r.dt, r.p, r.tau_tr, (double)other);
        ck_assert_msg(form == MPM_NGF_DK && mu_o >= r.par.mu_2 * (1.0 - 1e-9),
                      "form %d case %d: the other root %Lg >= 0 has mu %g < mu_2 %g",
                      form, n, other, mu_o, r.par.mu_2);
      }
    }
  }
  /* the sweep did reach the interesting regions */
  ck_assert_int_gt(both_positive, 1000);   /* tau_tr > S2: two positive roots */
  ck_assert_int_gt(near_s2, 10000);
  ck_assert_int_gt(gzero_flow, 1000);      /* g* = 0, tau_tr >= S2: must flow */
}
END_TEST

/* The discriminant identity used by the code, as a check of the algebra:
 * (beta u - mu_2 Gb g* + f v)^2 + 4 f dmu Gb g* tau_tr = b'^2 - 4 a c'
 * with u = tau_tr - S2, v = tau_tr - S0 (exact polynomials, so random values
 * agree to round-off of the larger side). */
START_TEST(t_discriminant_identity)
{
  unsigned long s = 99u;
  for (int n = 0; n < 10000; n++) {
    long double beta = 1.0L + lcg(&s), Gb = logu(&s, 1e-2, 1e2), gs = logu(&s, 1e-3, 1e3);
    long double f = lcg(&s), mus = lcg(&s), mu2 = mus + logu(&s, 1e-2, 50.0), p = logu(&s, 1, 1e3);
    long double tau = mu2 * p * 2.0L * lcg(&s), S0 = mus * p, S2 = mu2 * p;
    long double a = Gb * (beta * mu2 + f * mus);
    long double b = beta * (S2 - tau) - mu2 * Gb * gs + f * (S0 - tau), c = gs * (tau - S2);
    long double lhs = b * b - 4.0L * a * c;
    long double w = beta * (tau - S2) - mu2 * Gb * gs + f * (tau - S0);
    long double rhs = w * w + 4.0L * f * (mu2 - mus) * Gb * gs * tau;
    long double size = b * b + fabsl(4.0L * a * c);
    ck_assert(fabsl(lhs - rhs) <= 1e-15L * size);
  }
}
END_TEST

/* Through the material interface: the output satisfies, with mu = tau_{n+1}/p,
 *   split update, multiplied by (mu_2 - mu):
 *     dk:   (x - g* + c x)(mu_2 - mu) + f x (mu_s - mu) = 0
 *     hs21: (x - g* + c x) + k x (mu_s - mu) = 0
 *   stress: p_{n+1} = p_tr, tau_{n+1} = tau_tr p/(G dt x + p), sigma0_{n+1}
 *           parallel to sigma0_tr,
 *   flow rule: sigma_tr - sigma_{n+1} = G dt gdot_p N (= 2G dt Dp), N the unit
 *              deviator sigma0/tau, and gdot_p = x mu.
 * Each residual is bounded by 64 eps times the sum of the magnitudes of its
 * elementary terms; tau read back from the stress carries a few eps of
 * (tau + p) (the deviator is recovered next to the pressure), so mu carries a
 * few eps of (mu + 1). */
START_TEST(t_split_update_and_flow_rule)
{
  int checked = 0;
  for (int form = 0; form < 2; form++) {
    unsigned long s = 4242u + (unsigned long)form;
    mpm_material_params par = ngf_params(1e6, form);
    for (int n = 0; n < 20000; n++) {
      double dt = logu(&s, 1e-7, 1e-4), p0 = logu(&s, 1.0, 1e5);
      double mu0 = par.mu_2 * 1.2 * lcg(&s);
      mpm_sym3 s0 = stress(p0, mu0 * p0 * (lcg(&s) - 0.5), mu0 * p0 * (lcg(&s) - 0.5),
                           mu0 * p0 * (lcg(&s) - 0.5) * 0.5);
      mpm_mat3 L = plane_L(logu(&s, 1e-3, 10) * (lcg(&s) - 0.5), logu(&s, 1e-3, 1e2),
                           (lcg(&s) - 0.5), -logu(&s, 1e-3, 10) * lcg(&s));
      double g0 = lcg(&s) < 0.1 ? 0.0 : logu(&s, 1e-3, 1e3);
      double lap = (lcg(&s) - 0.5) * logu(&s, 1e-2, 1e8);
      mpm_mpoint pt = point(s0, 1600.0, g0, lap);
      mpm_material_ngf.update_point(&par, &L, dt, &pt, NULL);
      mpm_sym3 st = trial(&par, L, dt, s0);
      double p = mpm_sym3_pressure(st), tau_tr = mpm_sym3_tau(st);
      if (!(p > 0.0)) {
        ck_assert_int_eq(pt.state, MPM_STATE_DISCONNECTED);
        continue;
      }
      ck_assert_int_eq(pt.state, MPM_STATE_DENSE);
      double x = pt.g, k = dt / par.t0;
      double gs = fmax(0.0, g0 + k * par.A * par.A * par.d * par.d * lap);   /* g* */
      double mug = g0 * mpm_sym3_tau(s0) / mpm_sym3_pressure(s0);   /* mu_n g_n */
      double c = k * par.b * par.d * sqrt(par.rho_s / p) * mug, beta = 1.0 + c;
      double tau = mpm_sym3_tau(pt.sigma), mu = tau / p;
      const double tol = 64.0 * DBL_EPSILON;
      if (form == MPM_NGF_DK) {
        double f = k * par.dmu;
        double res = (beta * x - gs) * (par.mu_2 - mu) + f * x * (par.mu_s - mu);
        double size = (beta * x + gs) * (par.mu_2 + mu + 1.0) + f * x * (par.mu_s + mu + 1.0);
        ck_assert_msg(fabs(res) <= tol * size, "dk case %d: split residual %g of %g", n, res, size);
        ck_assert(mu < par.mu_2);
      } else {
        double res = (beta * x - gs) + k * x * (par.mu_s - mu);
        double size = beta * x + gs + k * x * (par.mu_s + mu + 1.0);
        ck_assert_msg(fabs(res) <= tol * size, "hs21 case %d: split residual %g of %g", n, res, size);
      }
      /* stress: pressure kept, deviator scaled by p/(G dt x + p) */
      ck_assert_double_eq_tol(mpm_sym3_pressure(pt.sigma), p, tol * p);
      ck_assert_double_eq_tol(tau * (par.G * dt * x + p), tau_tr * p,
                              tol * (tau_tr + p) * (par.G * dt * x + p));
      /* flow rule */
      ck_assert_double_le(fabs(pt.gdp - x * mu), tol * x * (mu + 1.0));
      mpm_sym3 d1 = mpm_sym3_dev(pt.sigma), d0 = mpm_sym3_dev(st);
      /* codirectional: sigma0_{n+1} tau_tr = sigma0_tr tau_{n+1} */
      ck_assert_double_le(sym3_maxabs(mpm_sym3_axpy(mpm_sym3_scale(d1, tau_tr), -tau, d0)),
                          tol * (tau + p) * tau_tr);
      /* sigma_tr - sigma_{n+1} = G dt gdot_p N, N = sigma0_tr/tau_tr = sigma0_{n+1}/tau_{n+1} */
      mpm_sym3 lhs = mpm_sym3_axpy(st, -1.0, pt.sigma);
      mpm_sym3 rhs = tau_tr > 0.0 ? mpm_sym3_scale(d0, par.G * dt * pt.gdp / tau_tr)
                                  : mpm_sym3_zero();
      ck_assert_double_le(sym3_maxabs(mpm_sym3_axpy(lhs, -1.0, rhs)),
                          tol * (sym3_maxabs(st) + p));
      checked++;
    }
  }
  ck_assert_int_gt(checked, 30000);
}
END_TEST

/* Steady simple shear L = gdot e_x (x) e_y under -p0 I, with A = 0 (lap
 * irrelevant). At a fixed point g_{n+1} = g* = g_n, so the split update reads
 *   dk:   Delta_mu (mu - mu_s)/(mu_2 - mu) = b sqrt(rho_s d^2/p) gdot_p  <=>  mu = mu(I),
 *   hs21: mu - mu_s = b I,
 * with I = gdot_p d sqrt(rho_s/p), for any dt (to round-off). As for mu_i,
 * gdot_p = gdot cos(theta) with 1 - cos(theta) ~ (tau/G)^2/2. */
static mpm_mpoint ngf_steady_shear(const mpm_material_params *par, double gdot, double p0,
                                   double g0, double dt, long nsteps, double *change)
{
  mpm_mat3 L = plane_L(0.0, gdot, 0.0, 0.0);
  mpm_mpoint pt = point(stress(p0, 0.0, 0.0, 0.0), 1600.0, g0, 0.0);
  for (long k = 0; k < nsteps; k++) {
    mpm_sym3 prev = pt.sigma;
    double gprev = pt.g;
    mpm_material_ngf.update_point(par, &L, dt, &pt, NULL);
    *change = fmax(sym3_maxabs(mpm_sym3_axpy(pt.sigma, -1.0, prev)) / p0,
                   fabs(pt.g - gprev) / pt.g);
  }
  return pt;
}

static double law(const mpm_material_params *par, double gdp, double p)
{
  double I = gdp * par->d * sqrt(par->rho_s / p);              /* I = gdot_p d sqrt(rho_s/p) */
  if (par->form == MPM_NGF_HS21)
    return par->mu_s + par->b * I;                             /* mu_s + b I */
  return par->mu_s + par->dmu / (par->I0 / I + 1.0);           /* mu(I) */
}

START_TEST(t_local_limit_is_mu_I)
{
  const double gdot = 1.0, p0 = 1000.0;
  for (int form = 0; form < 2; form++) {
    mpm_material_params par = ngf_params(1e7, form);
    par.A = 0.0;
    /* g relaxes on t0 = 1 ms, the stress on tau/(G gdot) ~ 1e-4 s: 0.2 s of
     * 1e-5 s steps are 200 t0. Start from rest with g = 0: the point loads
     * elastically until tau_tr >= S2, then fluidises by itself. */
    const double g_starts[] = {0.0, 3.0};
    for (int i = 0; i < 2; i++) {
      double change;
      mpm_mpoint a = ngf_steady_shear(&par, gdot, p0, g_starts[i], 1e-5, 20000, &change);
      double p = mpm_sym3_pressure(a.sigma), tau = mpm_sym3_tau(a.sigma), mu = tau / p;
      ck_assert_double_le(change, 1e-13);                      /* stationary */
      ck_assert_double_eq_tol(p, p0, 1e-12 * p0);
      ck_assert_double_eq_tol(mu, law(&par, a.gdp, p), 1e-12); /* the local law */
      ck_assert_double_eq_tol(a.gdp, a.g * mu, 1e-14 * a.gdp);
      double cos_t = a.sigma.xy / tau;
      ck_assert_double_le(1.0 - cos_t, 1e-7);
      ck_assert_double_eq_tol(mu, law(&par, gdot, p), 2.0 * par.dmu * (1.0 - cos_t) + 1e-12);
      ck_assert_double_gt(mu, par.mu_s + 0.005);               /* it does flow */
      /* the fixed point does not depend on dt */
      mpm_mpoint b = ngf_steady_shear(&par, gdot, p0, g_starts[i], 1e-4, 4000, &change);
      ck_assert_double_eq_tol(b.sigma.xy, a.sigma.xy, 1e-9 * tau);
      ck_assert_double_eq_tol(b.g, a.g, 1e-9 * a.g);
    }
  }
}
END_TEST

/* The mu_i steady state, seeded with g = gdot_p/mu, is a fixed point of the
 * NGF update with A = 0 (same law, same return relation tau_tr - tau = G dt gdot_p). */
START_TEST(t_seed_from_local)
{
  mpm_material_params par = ngf_params(1e7, MPM_NGF_DK);
  par.A = 0.0;
  mpm_mat3 L = plane_L(0.0, 1.0, 0.0, 0.0);
  mpm_mpoint pt = point(stress(1000.0, 0.0, 0.0, 0.0), 1600.0, 0.0, 0.0);
  for (int k = 0; k < 20000; k++)
    mpm_material_mu_i.update_point(&par, &L, 1e-5, &pt, NULL);
  double mu = mpm_sym3_tau(pt.sigma) / mpm_sym3_pressure(pt.sigma);
  pt.g = mpm_material_ngf_seed(pt.sigma, pt.gdp);
  ck_assert_double_eq_tol(pt.g * mu, pt.gdp, 1e-15 * pt.gdp);
  mpm_mpoint q = pt;
  for (int k = 0; k < 100; k++)
    mpm_material_ngf.update_point(&par, &L, 1e-5, &q, NULL);
  ck_assert_double_eq_tol(q.g, pt.g, 1e-11 * pt.g);
  ck_assert_double_eq_tol(q.sigma.xy, pt.sigma.xy, 1e-11 * fabs(pt.sigma.xy));
  ck_assert_double_eq_tol(q.gdp, pt.gdp, 1e-11 * pt.gdp);
  /* no seed from stress-free or unsheared states */
  ck_assert_double_eq(mpm_material_ngf_seed(mpm_sym3_zero(), 1.0), 0.0);
  ck_assert_double_eq(mpm_material_ngf_seed(stress(10.0, 0.0, 0.0, 0.0), 1.0), 0.0);
}
END_TEST

/* A loading that compresses, shears and extends (elastic, flowing,
 * disconnected, reconsolidated), with random Laplacians of either sign. */
static mpm_mat3 wild_L(double t)
{
  return plane_L(0.3 * sin(30.0 * t), 3.0 + 2.0 * sin(5.0 * t), -0.1 * cos(2.0 * t),
                 0.3 * sin(30.0 * t) - 0.05 * cos(t));
}

/* g >= 0 always; g = 0 when disconnected and on the first step after
 * reconsolidation when lap <= 0 and tau_tr < S2 (g* = 0). */
START_TEST(t_g_nonnegative)
{
  int disc = 0, reconnect = 0, flowing = 0;
  for (int form = 0; form < 2; form++) {
    mpm_material_params par = ngf_params(1e4, form);
    unsigned long s = 31u + (unsigned long)form;
    mpm_mpoint pt = point(stress(100.0, 0.0, 0.0, 0.0), 1600.0, 1.0, 0.0);
    const double dt = 1e-4;
    for (int k = 0; k < 100000; k++) {
      mpm_mat3 L = wild_L(k * dt);
      pt.lap = (lcg(&s) - 0.6) * logu(&s, 1.0, 1e9);
      int was_dense = mpm_sym3_pressure(pt.sigma) > 0.0;
      mpm_mpoint before = pt;
      mpm_material_ngf.update_point(&par, &L, dt, &pt, NULL);
      ck_assert(isfinite(pt.g) && pt.g >= 0.0);
      ck_assert(isfinite(pt.gdp) && pt.gdp >= 0.0);
      if (pt.state == MPM_STATE_DISCONNECTED) {
        ck_assert_double_eq(pt.g, 0.0);
        disc++;
      } else if (!was_dense) {
        reconnect++;
        mpm_sym3 st = trial(&par, L, dt, before.sigma);
        if (before.lap <= 0.0 && mpm_sym3_tau(st) < par.mu_2 * mpm_sym3_pressure(st)) {
          ck_assert_double_eq(pt.g, 0.0);                     /* g* = 0 */
          ck_assert_double_le(sym3_maxabs(mpm_sym3_axpy(pt.sigma, -1.0, st)),
                              1e-14 * sym3_maxabs(st));        /* elastic */
        }
      }
      flowing += pt.g > 0.0;
    }
  }
  ck_assert_int_gt(disc, 100);
  ck_assert_int_gt(reconnect, 10);
  ck_assert_int_gt(flowing, 1000);
}
END_TEST

/* Stress-free cases: rho < rho_c, tension, loss of the last pressure. */
START_TEST(t_disconnected)
{
  mpm_material_params par = ngf_params(1e4, MPM_NGF_DK);
  mpm_mat3 L = plane_L(0.2, 0.5, -0.1, 0.3);
  mpm_sym3 D0 = mpm_sym3_dev(mpm_mat3_sym(&L));
  double d0 = sqrt(2.0 * mpm_sym3_ddot(D0, D0));
  struct { mpm_sym3 s; double rho; } cases[] = {
    {stress(1000.0, 100.0, 50.0, 0.0), 1499.999},
    {stress(-10.0, 1.0, 2.0, 0.0), 1600.0},
    {stress(1e-3, 0.0, 0.0, 0.0), 1600.0},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    mpm_mpoint pt = point(cases[i].s, cases[i].rho, 5.0, 1e6);
    mpm_material_ngf.update_point(&par, &L, 1e-3, &pt, NULL);
    ck_assert_int_eq(pt.state, MPM_STATE_DISCONNECTED);
    ck_assert_double_eq(sym3_maxabs(pt.sigma), 0.0);
    ck_assert_double_eq(pt.g, 0.0);
    ck_assert_double_eq_tol(pt.gdp, d0, 1e-15 * d0);
  }
  /* the dense flag of the element average */
  ck_assert(mpm_material_ngf_dense(&par, stress(1.0, 0, 0, 0), par.rho_c));
  ck_assert(!mpm_material_ngf_dense(&par, stress(1.0, 0, 0, 0), par.rho_c * (1.0 - 1e-12)));
  ck_assert(!mpm_material_ngf_dense(&par, mpm_sym3_zero(), 1600.0));
}
END_TEST

/* p -> 0+ with g_n > 0 (c -> infinity): finite, x >= 0, tau <= mu_2 p (dk),
 * down to subnormal pressures. */
START_TEST(t_limits)
{
  const double ps[] = {1e-3, 1e-12, 1e-30, 1e-100, 1e-150, 1e-300, 4.9e-324};
  for (int form = 0; form < 2; form++) {
    mpm_material_params par = ngf_params(1e4, form);
    mpm_mat3 L = plane_L(0.0, 1.0, 0.0, 0.0);
    for (size_t i = 0; i < sizeof ps / sizeof ps[0]; i++) {
      mpm_mpoint pt = point(stress(ps[i], 0.0, 0.5 * ps[i], 0.0), 1600.0, 10.0, 1e3);
      pt.sigma.xx = pt.sigma.yy = pt.sigma.zz = -ps[i];          /* exact p = ps[i] */
      mpm_material_ngf.update_point(&par, &L, 1e-3, &pt, NULL);
      ck_assert_int_eq(pt.state, MPM_STATE_DENSE);
      ck_assert(isfinite(pt.g) && pt.g >= 0.0 && isfinite(pt.gdp));
      double tau = mpm_sym3_tau(pt.sigma), p = mpm_sym3_pressure(pt.sigma);
      ck_assert(isfinite(tau));
      if (form == MPM_NGF_DK)
        ck_assert_double_le(tau, par.mu_2 * p * (1.0 + 1e-12));
    }
    /* tau_tr = 0: no division by it */
    mpm_mat3 Z = plane_L(0, 0, 0, 0);
    mpm_mpoint q = point(stress(1000.0, 0.0, 0.0, 0.0), 1600.0, 2.0, 0.0);
    mpm_material_ngf.update_point(&par, &Z, 1e-3, &q, NULL);
    ck_assert_double_eq(q.sigma.xy, 0.0);
    ck_assert_double_eq(q.gdp, 0.0);
    ck_assert(q.g > 0.0 && q.g <= 2.0);                         /* decays, stays >= 0 */
  }
}
END_TEST

/* Explicit-diffusion number and its check; parameter checks; the table. */
START_TEST(t_check_and_table)
{
  mpm_material_params par = ngf_params(1e4, MPM_NGF_DK);
  mpm_err err = {0};
  ck_assert_int_eq(mpm_material_ngf.check(&par, &err), MPM_OK);
  /* A^2 d^2/t0 = 0.48^2 0.005^2 / 1e-3 = 5.76e-3 m^2/s; dx = dy = 1 mm:
   * 2/dx^2 + 2/dy^2 = 4e6 1/m^2; dt = 1e-4 s: 2.304 / n_sub */
  double r = mpm_material_ngf_diffusion_number(&par, 1e-4, 1, 1e-3, 1e-3, 0.0);
  ck_assert_double_eq_tol(r, 2.304, 1e-12);
  ck_assert_double_eq_tol(mpm_material_ngf_diffusion_number(&par, 1e-4, 3, 1e-3, 1e-3, 0.0), 0.768,
                          1e-12);
  ck_assert_double_eq_tol(mpm_material_ngf_diffusion_number(&par, 1e-4, 1, 2e-3, 1e-3, 0.0), 1.44,
                          1e-12);
  ck_assert_int_eq(mpm_material_ngf_check_diffusion(&par, 1e-4, 3, 1e-3, 1e-3, 0.0, &err), MPM_OK);
  ck_assert_int_eq(mpm_material_ngf_check_diffusion(&par, 1e-4, 2, 1e-3, 1e-3, 0.0, &err), MPM_EINPUT);
  ck_assert_msg(strstr(err.msg, "n_sub >= 3") != NULL, "%s", err.msg);
  ck_assert_int_eq(mpm_material_ngf_check_diffusion(&par, 1e-4, 0, 1e-3, 1e-3, 0.0, &err), MPM_EINPUT);
  /* 3D, dz = 1 mm: 2/dx^2 + 2/dy^2 + 2/dz^2 = 6e6 1/m^2, 3.456 / n_sub */
  ck_assert_double_eq_tol(mpm_material_ngf_diffusion_number(&par, 1e-4, 1, 1e-3, 1e-3, 1e-3), 3.456,
                          1e-12);
  ck_assert_int_eq(mpm_material_ngf_check_diffusion(&par, 1e-4, 3, 1e-3, 1e-3, 1e-3, &err),
                   MPM_EINPUT);
  ck_assert_msg(strstr(err.msg, "+ 2/dz^2") && strstr(err.msg, "n_sub >= 4"), "%s", err.msg);
  struct { const char *key; mpm_material_params par; } bad[] = {
    {"material.A", par}, {"material.t0", par}, {"material.t_seed", par},
    {"material.mu_2", par}, {"form", par},
  };
  bad[0].par.A = -0.1;
  bad[1].par.t0 = 0.0;
  bad[2].par.t_seed = -1.0;
  bad[3].par.mu_2 = par.mu_s;
  bad[4].par.form = 2;
  for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
    mpm_err e = {0};
    ck_assert_int_eq(mpm_material_ngf.check(&bad[i].par, &e), MPM_EINPUT);
    ck_assert_msg(strstr(e.msg, bad[i].key) != NULL, "'%s' does not name %s", e.msg, bad[i].key);
  }
  ck_assert_ptr_eq(mpm_material_lookup("ngf"), &mpm_material_ngf);
  ck_assert_int_eq(mpm_material_ngf.nonlocal, 1);
  ck_assert_int_eq(mpm_material_mu_i.nonlocal, 0);
  ck_assert_int_eq(mpm_material_elastic.nonlocal, 0);
  ck_assert_int_eq(mpm_material_ngf_form_from_name("dk"), MPM_NGF_DK);
  ck_assert_int_eq(mpm_material_ngf_form_from_name("hs21"), MPM_NGF_HS21);
  ck_assert_int_eq(mpm_material_ngf_form_from_name("DK"), -1);
  ck_assert_str_eq(mpm_material_ngf_form_name(MPM_NGF_HS21), "hs21");
  ck_assert_ptr_null(mpm_material_ngf_form_name(7));
}
END_TEST

int main(void)
{
  Suite *s = suite_create("ngf");
  TCase *tc = tcase_create("ngf");
  tcase_set_timeout(tc, 120);
  tcase_add_test(tc, t_root_solves_quadratic);
  tcase_add_test(tc, t_root_is_physical);
  tcase_add_test(tc, t_discriminant_identity);
  tcase_add_test(tc, t_split_update_and_flow_rule);
  tcase_add_test(tc, t_local_limit_is_mu_I);
  tcase_add_test(tc, t_seed_from_local);
  tcase_add_test(tc, t_g_nonnegative);
  tcase_add_test(tc, t_disconnected);
  tcase_add_test(tc, t_limits);
  tcase_add_test(tc, t_check_and_table);
  suite_add_tcase(s, tc);
  SRunner *sr = srunner_create(s);
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf ? EXIT_FAILURE : EXIT_SUCCESS;
}
