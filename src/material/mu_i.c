/* mu_i.c: the trans-phase mu(I) material of [DK15] §2-3.2, MODEL.md section 4.
 *
 * Dense: Jaumann hypoelastic-viscoplastic, sigma^ = C:(D - Dp),
 *   Dp = gdot_p sigma0 / (2 tau), tau = p mu(I), mu(I) = mu_s + dmu / (I0/I + 1),
 *   I = gdot_p d sqrt(rho_s / p)                                  [DK15 eq. 2.6-2.13].
 * Disconnected (rho < rho_c, or trial pressure p_tr <= 0): sigma = 0 [DK15 eq. 2.14].
 *
 * One step with L fixed (MODEL.md section 4, [DK15] eq. 3.10-3.16):
 *   sigma_tr = sigma_n + dt (C:D + W sigma_n - sigma_n W),   p_tr = -tr(sigma_tr)/3,
 *   S0 = mu_s p_tr, S2 = mu_2 p_tr, alpha = xi G dt sqrt(p_tr),
 *   B = S2 + tau_tr + alpha, H = S2 tau_tr + S0 alpha,
 *   tau_tr <= S0: sigma = sigma_tr (elastic);
 *   otherwise tau = 2H / (B + sqrt(B^2 - 4H)) (small root of tau^2 - B tau + H = 0,
 *   the form without cancellation), sigma = (tau/tau_tr) sigma0_tr - p_tr I,
 *   gdot_p = (tau_tr - tau) / (G dt).
 * The discriminant is evaluated as the algebraically equal sum
 *   B^2 - 4H = (S2 - tau_tr)^2 + alpha (alpha + 2 (S2 - S0) + 2 (tau_tr - S0)),
 * every term of which is >= 0 when tau_tr > S0 (S2 > S0): no cancellation and never
 * negative, so the square root is always defined. The terms are first scaled
 * by an exact power of two near the largest, so nothing under- or overflows
 * as p -> 0+. The small root lies in
 * (S0, min(S2, tau_tr)): mu_s < mu < mu_2 and gdot_p > 0.
 *
 * gdot_p of a disconnected point: its stress is identically zero, so its elastic
 * strain rate is zero and its whole deviatoric rate is inelastic,
 *   gdot_p = sqrt(2 D0:D0),
 * which is also the limit of the dense update as p -> 0+ (there tau <= mu_2 p -> 0
 * and all of G dt sqrt(2 D0:D0) is returned as plastic flow). gdot_p is therefore
 * continuous across disconnection and reconnection.
 * mpm_material_mu_i_gdp gives gdot_p from a stress (the law inverted):
 *   gdot_p = xi sqrt(p) (mu - mu_s) / (mu_2 - mu) for mu_s < mu < mu_2, 0 below.
 * dt <= 0 leaves the trial stress (no plastic step is defined without time). */
#include "material/material.h"

#include <math.h>

#include "core/points.h"

/* Stress-free point: sigma = 0, gdot_p = sqrt(2 D0:D0). */
static inline mpm_mpoint mu_i_disconnect(mpm_sym3 D, mpm_mpoint pt)
{
  pt.sigma = mpm_sym3_zero();
  pt.gdp = mpm_material_free_gdp(D);
  pt.state = MPM_STATE_DISCONNECTED;
  return pt;
}

double mpm_material_mu_i_gdp(const mpm_material_params *par, mpm_sym3 sigma, mpm_sym3 D,
                             int state)
{
  if (state == MPM_STATE_DISCONNECTED)
    return mpm_material_free_gdp(D);                              /* sqrt(2 D0:D0) */
  double p = mpm_sym3_pressure(sigma), tau = mpm_sym3_tau(sigma);
  if (!(p > 0.0))
    return 0.0;
  double mu = tau / p;
  if (mu <= par->mu_s)
    return 0.0;
  if (mu >= par->mu_2)
    return INFINITY;
  return par->xi * sqrt(p) * (mu - par->mu_s) / (par->mu_2 - mu);  /* mu(I) inverted */
}

/* Small root of tau^2 - B tau + H = 0 for tau_tr > S0 >= 0 (see banner),
 * with B = S2 + tau_tr + alpha and H = S2 tau_tr + S0 alpha. */
static inline double mu_i_small_root(double tau_tr, double S0, double S2, double alpha)
{
  double B = S2 + tau_tr + alpha;                                  /* B */
  double H = S2 * tau_tr + S0 * alpha;                             /* H */
  double disc = (S2 - tau_tr) * (S2 - tau_tr)                      /* B^2 - 4H */
              + alpha * (alpha + 2.0 * (S2 - S0) + 2.0 * (tau_tr - S0));
  return 2.0 * H / (B + sqrt(disc));                               /* 2H / (B + sqrt) */
}

/* The small root with its inputs scaled by the power of two of the largest,
 * m = max(tau_tr, S2, alpha), and the root scaled back: exact, and as
 * p -> 0+ the products in H and B^2 can then neither underflow nor overflow
 * (mpm_material_pow2). */
static inline double mu_i_return_tau(double tau_tr, double S0, double S2, double alpha)
{
  double m = tau_tr > S2 ? tau_tr : S2;
  m = alpha > m ? alpha : m;                                       /* max(tau_tr, S2, alpha) */
  double down, up;
  mpm_material_pow2(m, &down, &up);
  return mu_i_small_root(tau_tr * down, S0 * down, S2 * down, alpha * down) * up;
}

/* One update (see the top of this file) of the point pt, by value: the
 * kernel of update and update_point. */
MPM_MATERIAL_KERNEL mpm_mpoint mu_i_step(const mpm_material_params *par, mpm_mat3 L, double dt,
                                         mpm_mpoint pt)
{
  mpm_sym3 D = mpm_mat3_sym(&L);
  if (!(pt.rho >= par->rho_c))                                     /* rho_{n+1} < rho_c */
    return mu_i_disconnect(D, pt);
  mpm_sym3 s_tr = mpm_material_trial(par, D, &L, pt.sigma, dt);   /* sigma_tr */
  double p_tr = mpm_sym3_pressure(s_tr);                           /* p_tr = -tr/3 */
  if (!(p_tr > 0.0))                                               /* p_tr <= 0 (or NaN) */
    return mu_i_disconnect(D, pt);
  pt.state = MPM_STATE_DENSE;
  mpm_sym3 s0_tr = mpm_sym3_dev(s_tr);                             /* sigma0_tr */
  double tau_tr = sqrt(0.5 * mpm_sym3_ddot(s0_tr, s0_tr));         /* tau_tr */
  double S0 = par->mu_s * p_tr, S2 = par->mu_2 * p_tr;
  if (tau_tr <= S0 || !(dt > 0.0)) {                               /* below yield */
    pt.sigma = s_tr;
    pt.gdp = 0.0;
    return pt;
  }
  double alpha = par->xi * par->G * dt * sqrt(p_tr);               /* xi G dt sqrt(p) */
  double tau = mu_i_return_tau(tau_tr, S0, S2, alpha);
  pt.sigma = mpm_sym3_add_iso(mpm_sym3_scale(s0_tr, tau / tau_tr), -p_tr);
  pt.gdp = (tau_tr - tau) / (par->G * dt);                         /* gdot_p */
  return pt;
}

static void mu_i_update_point(const mpm_material_params *par, const mpm_mat3 *L, double dt,
                              mpm_mpoint *pt, mpm_mdeform *def)
{
  (void)def;   /* no deformation gradients */
  *pt = mu_i_step(par, *L, dt, *pt);
}

/* Parameter ranges this model needs (names the key, as the input reader expects). */
static int mu_i_check(const mpm_material_params *par, mpm_err *err)
{
  int rc = mpm_material_check_elastic(par, err);
  if (rc != MPM_OK)
    return rc;
  if (!(par->rho_s > 0.0 && isfinite(par->rho_s)))
    return mpm_err_set(err, MPM_EINPUT, "key 'material.rho_s' = %g: must be > 0 kg/m^3",
                       par->rho_s);
  if (!(par->rho_c > 0.0 && par->rho_c <= par->rho_s))
    return mpm_err_set(err, MPM_EINPUT,
                       "key 'material.rho_c' = %g: allowed range (0, rho_s = %g] kg/m^3",
                       par->rho_c, par->rho_s);
  if (!(par->mu_s >= 0.0 && isfinite(par->mu_s)))
    return mpm_err_set(err, MPM_EINPUT, "key 'material.mu_s' = %g: must be >= 0", par->mu_s);
  if (!(par->mu_2 > par->mu_s && isfinite(par->mu_2)))
    return mpm_err_set(err, MPM_EINPUT, "key 'material.mu_2' = %g: must be > mu_s = %g",
                       par->mu_2, par->mu_s);
  if (!(par->I0 > 0.0 && isfinite(par->I0)))
    return mpm_err_set(err, MPM_EINPUT, "key 'material.I0' = %g: must be > 0", par->I0);
  if (!(par->d > 0.0 && isfinite(par->d)))
    return mpm_err_set(err, MPM_EINPUT, "key 'material.d' = %g: must be > 0 m", par->d);
  return MPM_OK;
}

/* A batch of points, the update above inlined. */
static void mu_i_update(const mpm_material_params *par, double dt, int nsub,
                        const mpm_material_batch *b)
{
  mpm_material_loop(par, dt, nsub, b, mu_i_step);
}

const mpm_material_type mpm_material_mu_i = {
  .name = "mu_i",
  .description = "trans-phase mu(I): Jaumann elastic, mu(I) flow, stress-free below rho_c [DK15]",
  .check = mu_i_check,
  .update = mu_i_update,
  .update_point = mu_i_update_point,
};
