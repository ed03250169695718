/* ngf.c: the trans-phase nonlocal granular fluidity material of [DK-silo]
 * §4-5 (MODEL.md section 5 steps 3-5), the per-point part.
 *
 * PDE (dense): t0 dg/dt = A^2 d^2 lap(g) - F(mu) g - b sqrt(rho_s d^2/p) mu g^2,
 *   F = Delta_mu (mu_s - mu)/(mu_2 - mu)  ([DK-silo] eq. 2.1, form "dk"), or
 *   F = mu_s - mu                          ([HS21] eq. 6, linearised, form "hs21");
 * flow rule gdot_p = g mu, Dp = gdot_p sigma0 / (2 tau); Jaumann elasticity.
 * Disconnected (rho_{n+1} < rho_c or p_tr <= 0): sigma = 0, g = 0. A point that
 * was not dense at the start of the step (p_n <= 0) starts it with g_n = 0
 * ([DK-silo] §4: reconsolidated material starts with g = 0).
 *
 * One (sub)step with L fixed and lap_e of the point's unit given (pt->lap):
 *   sigma_tr = sigma_n + dt (C:D + W sigma_n - sigma_n W),  p = -tr(sigma_tr)/3,
 *   g* = max(0, g_n + (dt/t0) A^2 d^2 lap_e)                       [eq. 5.3]
 *   x = g_{n+1} solves x - g* = -k x F(mu(x)) - c x with k = dt/t0,
 *   c = k b sqrt(rho_s d^2/p) mu_n g_n, mu(x) = tau_tr/(G dt x + p)   [eq. 5.4-5.5]
 *   (p^-1/2 in c: the unit mean pt->isp, or the point's own, material.p_sample)
 *   tau = tau_tr p/(G dt x + p), sigma = (tau/tau_tr) sigma0_tr - p I,
 *   gdot_p = x mu(x)                                              [eq. 5.5, 5.9]
 * Multiplied out (Gb = G dt, beta = 1 + c, S0 = mu_s p, S2 = mu_2 p, f = k Delta_mu):
 *   dk:   a = Gb (beta mu_2 + f mu_s), b' = beta (S2 - tau_tr) - mu_2 Gb g* + f (S0 - tau_tr),
 *         c' = g* (tau_tr - S2)                       (MODEL.md: eq. 5.6-5.7 / sqrt(p))
 *   hs21: a = Gb (beta + k mu_s), b' = beta p - Gb g* + k (S0 - tau_tr), c' = -g* p.
 * Root: x = 0 if g* = 0 and tau_tr < S2 (no spontaneous fluidisation); else the
 * larger root, x = (-b' + sqrt(disc))/(2a) for b' < 0, x = 2c'/(-b' - sqrt(disc))
 * otherwise (no cancellation). The discriminant is evaluated as a sum of
 * non-negative terms (algebraically equal to b'^2 - 4ac'):
 *   dk:   disc = (beta (tau_tr - S2) - mu_2 Gb g* + f (tau_tr - S0))^2 + 4 f Delta_mu Gb g* tau_tr
 *   hs21: disc = b'^2 + 4 a g* p. */
#include "material/material.h"

#include <math.h>
#include <string.h>

#include "core/names.h"
#include "core/points.h"

static const char *const form_names[] = {"dk", "hs21"};
static const char *const p_sample_names[] = {"point", "unit"};

int mpm_material_ngf_form_from_name(const char *name)
{
  return mpm_names_index(form_names, MPM_NAMES_COUNT(form_names), name);
}

const char *mpm_material_ngf_form_name(int form)
{
  return mpm_names_at(form_names, MPM_NAMES_COUNT(form_names), form);
}

int mpm_material_ngf_p_sample_from_name(const char *name)
{
  return mpm_names_index(p_sample_names, MPM_NAMES_COUNT(p_sample_names), name);
}

const char *mpm_material_ngf_p_sample_name(int sample)
{
  return mpm_names_at(p_sample_names, MPM_NAMES_COUNT(p_sample_names), sample);
}

int mpm_material_ngf_dense(const mpm_material_params *par, mpm_sym3 sigma_n, double rho)
{
  return mpm_sym3_pressure(sigma_n) > 0.0 && rho >= par->rho_c;   /* p_n > 0, rho >= rho_c */
}

double mpm_material_ngf_seed(mpm_sym3 sigma, double gdp)
{
  double p = mpm_sym3_pressure(sigma), tau = mpm_sym3_tau(sigma);
  return p > 0.0 && tau > 0.0 ? gdp * p / tau : 0.0;              /* g = gdot_p / mu */
}

/* Quadratic a x^2 + b x + c = 0 and its discriminant, scaled together. */
typedef struct ngf_quad { double a, b, c, disc; } ngf_quad;

/* The exact powers of two (mpm_material_pow2) of the quadratic's size
 * m = |t[0]| + |t[1]| + |t[2]| + sqrt|a| sqrt|c| (t the terms whose sum makes
 * b): scaled by them, b^2 and a c are near 1, so nothing under- or overflows
 * as p -> 0+; m = 0 or not finite: no scaling. */
static inline void quad_scale(double a, double c, const double t[3], double *down, double *up)
{
  const double m = fabs(t[0]) + fabs(t[1]) + fabs(t[2]) + sqrt(fabs(a)) * sqrt(fabs(c));
  mpm_material_pow2(m, down, up);
}

/* dk form: terms T1 = beta (tau_tr - S2), T2 = mu_2 Gb g*, T3 = f (tau_tr - S0). */
static inline ngf_quad quad_dk(const mpm_material_params *par, double Gb, double p, double tau_tr,
                               double gs, double k, double beta)
{
  double f = k * par->dmu;                                          /* f = k Delta_mu */
  double t[3] = {beta * (tau_tr - par->mu_2 * p), par->mu_2 * Gb * gs,
                 f * (tau_tr - par->mu_s * p)};
  double a = Gb * (beta * par->mu_2 + f * par->mu_s);               /* a */
  double c = gs * (tau_tr - par->mu_2 * p);                         /* c' */
  double sd, su;
  quad_scale(a, c, t, &sd, &su);
  t[0] *= sd;
  t[1] *= sd;
  t[2] *= sd;
  double r = f * par->dmu * tau_tr * sd * (Gb * gs * sd);           /* f dmu Gb g* tau_tr */
  double bb = t[0] - t[1] + t[2];
  return (ngf_quad){a * sd, -(t[0] + t[1] + t[2]), c * sd, bb * bb + 4.0 * r};
}

/* hs21 form: terms T1 = beta p, T2 = -Gb g*, T3 = k (S0 - tau_tr). */
static inline ngf_quad quad_hs21(const mpm_material_params *par, double Gb, double p, double tau_tr,
                                 double gs, double k, double beta)
{
  double t[3] = {beta * p, -Gb * gs, k * (par->mu_s * p - tau_tr)};
  double a = Gb * (beta + k * par->mu_s);                           /* a */
  double c = -gs * p;                                               /* c' */
  double sd, su;
  quad_scale(a, c, t, &sd, &su);
  t[0] *= sd;
  t[1] *= sd;
  t[2] *= sd;
  a *= sd;
  c *= sd;
  double b = t[0] + t[1] + t[2];
  return (ngf_quad){a, b, c, b * b - 4.0 * a * c};                  /* -4ac' >= 0 */
}

/* Larger root without cancellation. */
static inline double larger_root(ngf_quad q)
{
  double sq = sqrt(q.disc > 0.0 ? q.disc : 0.0);
  if (q.b < 0.0)
    return (-q.b + sq) / (2.0 * q.a);                               /* (-b + sqrt)/(2a) */
  double den = -q.b - sq;
  double x = den < 0.0 ? 2.0 * q.c / den : 0.0;                     /* 2c/(-b - sqrt) */
  return x > 0.0 ? x : 0.0;
}

static inline double ngf_fluidity(const mpm_material_params *par, double dt, double p,
                                   double tau_tr, double gstar, double mug_n, double isp)
{
  if (!(dt > 0.0))
    return gstar;
  if (gstar == 0.0 && tau_tr < par->mu_2 * p)
    return 0.0;                                                     /* g = 0 stays */
  double k = dt / par->t0;                                          /* k = dt/t0 */
  double Gb = par->G * dt;                                          /* Gb = G dt */
  if (!(isp > 0.0))
    isp = 1.0 / sqrt(p);                                            /* the point's p^-1/2 */
  double c = k * par->b * par->d * sqrt(par->rho_s) * isp * mug_n;  /* k b sqrt(rho_s d^2/p) mu_n g_n */
  double beta = 1.0 + c;
  ngf_quad q = par->form == MPM_NGF_HS21 ? quad_hs21(par, Gb, p, tau_tr, gstar, k, beta)
                                         : quad_dk(par, Gb, p, tau_tr, gstar, k, beta);
  return larger_root(q);
}

double mpm_material_ngf_fluidity(const mpm_material_params *par, double dt, double p, double tau_tr,
                                 double gstar, double mug_n, double isp)
{
  return ngf_fluidity(par, dt, p, tau_tr, gstar, mug_n, isp);
}

/* Stress-free point: sigma = 0, g = 0, gdot_p = sqrt(2 D0:D0) (as mu_i). */
static inline mpm_mpoint ngf_disconnect(mpm_sym3 D, mpm_mpoint pt)
{
  pt.sigma = mpm_sym3_zero();
  pt.g = 0.0;
  pt.gdp = mpm_material_free_gdp(D);
  pt.state = MPM_STATE_DISCONNECTED;
  return pt;
}

double mpm_material_ngf_diffusivity(const mpm_material_params *par, double dt)
{
  return dt / par->t0 * par->A * par->A * par->d * par->d;         /* (dt/t0) A^2 d^2 */
}

/* g* = max(0, g_n + (dt/t0) A^2 d^2 lap_e); NaN propagates to the stress. */
static inline double ngf_gstar(const mpm_material_params *par, double dt, double g_n, double lap)
{
  double gs = g_n + mpm_material_ngf_diffusivity(par, dt) * lap;   /* g_n + c lap */
  return gs < 0.0 ? 0.0 : gs;
}

double mpm_material_ngf_gstar(const mpm_material_params *par, double dt, double g_n, double lap)
{
  return ngf_gstar(par, dt, g_n, lap);
}

/* The return for fluidity x >= 0 of a dense point with trial stress s_tr,
 * p = p_tr > 0: tau = tau_tr p / (G dt x + p) (eq. 5.5: tau_{n+1} =
 * tau_tr - G dt gdot_p with gdot_p = x mu_{n+1}), sigma = (tau/tau_tr)
 * sigma0_tr - p I, g = x, gdot_p = x mu_{n+1}. */
static inline mpm_mpoint ngf_return(const mpm_material_params *par, double dt, mpm_sym3 s_tr,
                                    double p, double x, mpm_mpoint pt)
{
  mpm_sym3 s0_tr = mpm_sym3_dev(s_tr);
  double tau_tr = sqrt(0.5 * mpm_sym3_ddot(s0_tr, s0_tr));         /* tau_tr */
  double r = mpm_material_ngf_return_ratio(par, dt, p, x);         /* tau / tau_tr */
  pt.sigma = mpm_sym3_add_iso(mpm_sym3_scale(s0_tr, r), -p);      /* (tau/tau_tr) s0_tr - p I */
  pt.g = x;
  pt.gdp = x * r * tau_tr / p;                                     /* gdot_p = x mu(x) */
  pt.state = MPM_STATE_DENSE;
  return pt;
}

/* The trial stress s_tr of a (sub)step and p = p_tr; 0 when the point
 * disconnects instead (rho_{n+1} < rho_c or p_tr <= 0). */
static inline int ngf_trial(const mpm_material_params *par, const mpm_mat3 *L, double dt,
                            const mpm_mpoint *pt, mpm_sym3 *s_tr, double *p)
{
  if (!(pt->rho >= par->rho_c))                                     /* rho_{n+1} < rho_c */
    return 0;
  *s_tr = mpm_material_trial(par, mpm_mat3_sym(L), L, pt->sigma, dt);  /* sigma_tr */
  *p = mpm_sym3_pressure(*s_tr);                                   /* p = p_tr */
  return *p > 0.0;
}

/* One (sub)step (see the top of this file) of the point pt, by value: the
 * kernel of update and update_point. */
MPM_MATERIAL_KERNEL mpm_mpoint ngf_step(const mpm_material_params *par, mpm_mat3 L, double dt,
                                        mpm_mpoint pt)
{
  double p_n = mpm_sym3_pressure(pt.sigma);
  double g_n = p_n > 0.0 ? pt.g : 0.0;                              /* reconsolidated: g = 0 */
  double mug_n = p_n > 0.0 ? g_n * mpm_sym3_tau(pt.sigma) / p_n : 0.0;  /* mu_n g_n */
  mpm_sym3 s_tr;
  double p;
  if (!ngf_trial(par, &L, dt, &pt, &s_tr, &p))
    return ngf_disconnect(mpm_mat3_sym(&L), pt);
  double tau_tr = mpm_sym3_tau(s_tr);                              /* tau_tr */
  double gs = ngf_gstar(par, dt, g_n, pt.lap);                     /* g* */
  double x = ngf_fluidity(par, dt, p, tau_tr, gs, mug_n, pt.isp);  /* g_{n+1} */
  return ngf_return(par, dt, s_tr, p, x, pt);
}

static void ngf_update_point(const mpm_material_params *par, const mpm_mat3 *L, double dt,
                             mpm_mpoint *pt, mpm_mdeform *def)
{
  (void)def;   /* no deformation gradients */
  *pt = ngf_step(par, *L, dt, *pt);
}

/* Steady form ([D-thesis] eq. 2.28-2.30; MODEL.md section 6), the linear
 * local law mu = mu_s + b I of form "hs21" (input_check allows no other):
 *   c = |mu - mu_s| = (A d / xi)^2,
 *   g_loc = sqrt(p / (rho_s d^2)) (mu - mu_s) / (b mu) for mu > mu_s, else 0,
 * from sigma at the start of the step, as [D-thesis] Algorithm 2. Dividing
 * by xi^2 is never needed: the solve multiplies by c, so mu = mu_s (xi
 * infinite) is c = 0, no guard. */
static void ngf_steady_terms(const mpm_material_params *par, mpm_sym3 sigma, double *c,
                             double *gloc)
{
  double p = mpm_sym3_pressure(sigma);
  *c = *gloc = 0.0;
  if (!(p > 0.0))
    return;
  double mu = mpm_sym3_tau(sigma) / p;
  *c = fabs(mu - par->mu_s);                                       /* |mu - mu_s| */
  if (mu > par->mu_s)                                              /* sqrt(p/(rho_s d^2)) (mu-mu_s)/(b mu) */
    *gloc = sqrt(p / par->rho_s) / par->d * (mu - par->mu_s) / (par->b * mu);
}

/* The update with the fluidity of a steady solve: pt.g is g_{n+1} (by value,
 * the kernel of update_steady and update_steady_point). */
MPM_MATERIAL_KERNEL mpm_mpoint ngf_steady_step(const mpm_material_params *par, mpm_mat3 L,
                                               double dt, mpm_mpoint pt)
{
  mpm_sym3 s_tr;
  double p;
  if (!ngf_trial(par, &L, dt, &pt, &s_tr, &p))
    return ngf_disconnect(mpm_mat3_sym(&L), pt);
  return ngf_return(par, dt, s_tr, p, pt.g > 0.0 ? pt.g : 0.0, pt);  /* g_{n+1} = max(g, 0) */
}

static void ngf_update_steady_point(const mpm_material_params *par, const mpm_mat3 *L, double dt,
                                    mpm_mpoint *pt, mpm_mdeform *def)
{
  (void)def;   /* no deformation gradients */
  *pt = ngf_steady_step(par, *L, dt, *pt);
}

/* A batch of points with the fluidity of a steady solve. */
static void ngf_update_steady(const mpm_material_params *par, double dt, int nsub,
                              const mpm_material_batch *b)
{
  mpm_material_loop(par, dt, nsub, b, ngf_steady_step);
}

static int ngf_check(const mpm_material_params *par, mpm_err *err)
{
  int rc = mpm_material_mu_i.check(par, err);                     /* E, nu, rho, mu(I), d */
  if (rc != MPM_OK)
    return rc;
  if (!(par->A >= 0.0 && isfinite(par->A)))
    return mpm_err_set(err, MPM_EINPUT, "key 'material.A' = %g: must be >= 0", par->A);
  if (!(par->t0 > 0.0 && isfinite(par->t0)))
    return mpm_err_set(err, MPM_EINPUT, "key 'material.t0' = %g: must be > 0 s", par->t0);
  if (!mpm_material_ngf_form_name(par->form))
    return mpm_err_set(err, MPM_EINPUT,
                       "key 'material.form' = %d: unknown (allowed: \"dk\", \"hs21\")", par->form);
  if (!mpm_material_ngf_p_sample_name(par->p_sample))
    return mpm_err_set(err, MPM_EINPUT,
                       "key 'material.p_sample' = %d: unknown (allowed: \"point\", \"unit\")",
                       par->p_sample);
  if (!(par->t_seed >= 0.0 && isfinite(par->t_seed)))
    return mpm_err_set(err, MPM_EINPUT, "key 'material.t_seed' = %g: must be >= 0 s",
                       par->t_seed);
  return MPM_OK;
}

double mpm_material_ngf_diffusion_number(const mpm_material_params *par, double dt, int n_sub,
                                         double dx, double dy, double dz)
{
  const double z = dz > 0.0 ? 2.0 / (dz * dz) : 0.0;
  return mpm_material_ngf_diffusivity(par, dt / n_sub) * (2.0 / (dx * dx) + 2.0 / (dy * dy) + z);
}

int mpm_material_ngf_check_diffusion(const mpm_material_params *par, double dt, int n_sub,
                                     double dx, double dy, double dz, mpm_err *err)
{
  if (n_sub < 1)
    return mpm_err_set(err, MPM_EINPUT, "NGF substeps n_sub = %d: must be >= 1", n_sub);
  double r = mpm_material_ngf_diffusion_number(par, dt, n_sub, dx, dy, dz);
  if (r <= 1.0)
    return MPM_OK;
  double need = ceil(mpm_material_ngf_diffusion_number(par, dt, 1, dx, dy, dz));
  return mpm_err_set(err, MPM_EINPUT,
                     "NGF explicit diffusion unstable: (dt/n_sub) A^2 d^2/t0 (2/dx^2 + 2/dy^2%s)"
                     " = %.4g > 1 with dt = %g s, n_sub = %d; needs n_sub >= %.0f",
                     dz > 0.0 ? " + 2/dz^2" : "", r, dt,
                     n_sub, need);
}

/* A batch of points, the update above inlined. */
static void ngf_update(const mpm_material_params *par, double dt, int nsub,
                       const mpm_material_batch *b)
{
  mpm_material_loop(par, dt, nsub, b, ngf_step);
}

const mpm_material_type mpm_material_ngf = {
  .name = "ngf",
  .description = "trans-phase nonlocal granular fluidity: Jaumann elastic, flow rule gdot_p = g mu, "
                 "diffusion of g (explicit or implicit) and semi-implicit local update of g [DK-silo]",
  .check = ngf_check,
  .update = ngf_update,
  .update_point = ngf_update_point,
  .nonlocal = 1,
  .dense = mpm_material_ngf_dense,
  .before_seed = &mpm_material_mu_i,
  .seed = mpm_material_ngf_seed,
  .steady_terms = ngf_steady_terms,
  .update_steady = ngf_update_steady,
  .update_steady_point = ngf_update_steady_point,
};
