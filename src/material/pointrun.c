/* pointrun.c: one material point under a prescribed history: the discrete
 * update run step by step, the recorded quantities, error norms and orders
 * (reference.h; MODEL.md section 4).
 *
 * Step k: L_k from the history (default: exact mean over the step),
 *   rho_{k+1} = rho_k exp(-dt tr L_k)          (MODEL.md section 2 step 5),
 *   sigma_{k+1}, gdot_p from the model with rho_{k+1}.
 * Recorded: p = -tr(sigma)/3, tau = sqrt(sigma0:sigma0/2), mu = tau/p (0 if p <= 0),
 *   Dp = gdot_p sigma0 / (2 tau) if tau > 0, else gdot_p D0 / sqrt(2 D0:D0)
 *   (stress-free: Dp = D0 since gdot_p = sqrt(2 D0:D0) there).
 * Error: e_f = sqrt(sum_k w_k (a_k - r_k)^2) / sqrt(sum_k w_k r_k^2), w_k = t_k - t_{k-1};
 * order: least-squares slope of log e against log dt. */
#include "material/reference.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/points.h"

#define MPM_SERIES_NAME_(e, name) name,
static const char *const series_names[MPM_SER_N] = {MPM_SERIES_FIELDS(MPM_SERIES_NAME_)};
#undef MPM_SERIES_NAME_

const char *mpm_series_name(int field)
{
  return field >= 0 && field < MPM_SER_N ? series_names[field] : NULL;
}

mpm_series *mpm_series_alloc(size_t n)
{
  mpm_series *s = calloc(1, sizeof *s);
  if (!s)
    return NULL;
  s->n = n;
  s->t = calloc(n ? n : 1, sizeof *s->t);
  s->v = calloc((n ? n : 1) * MPM_SER_N, sizeof *s->v);
  if (!s->t || !s->v) {
    mpm_series_free(s);
    return NULL;
  }
  return s;
}

void mpm_series_free(mpm_series *s)
{
  if (!s)
    return;
  free(s->t);
  free(s->v);
  free(s);
}

int mpm_sample_lookup(const char *name)
{
  static const char *const names[] = {"mean", "start", "mid", "end"};
  for (int i = 0; i < 4; i++)
    if (strcmp(name, names[i]) == 0)
      return i;
  return -1;
}

/* ------------------------------------------------------------ recording */

void mpm_series_record(mpm_series *s, size_t k, const mpm_point_rec *r)
{
  mpm_sym3 s0 = mpm_sym3_dev(r->sigma);
  double p = mpm_sym3_pressure(r->sigma);
  double tau = sqrt(0.5 * mpm_sym3_ddot(s0, s0));
  mpm_sym3 Dp = mpm_sym3_zero(), D0 = mpm_sym3_dev(r->D);
  double d0 = sqrt(2.0 * mpm_sym3_ddot(D0, D0));               /* sqrt(2 D0:D0) */
  if (tau > 0.0)
    Dp = mpm_sym3_scale(s0, r->gdp / (2.0 * tau));             /* gdot_p s0 / 2 tau */
  else if (r->gdp > 0.0 && d0 > 0.0)
    Dp = mpm_sym3_scale(D0, r->gdp / d0);                      /* stress-free: along D0 */
  double val[MPM_SER_N] = {
    [MPM_SER_SXX] = r->sigma.xx, [MPM_SER_SYY] = r->sigma.yy,
    [MPM_SER_SZZ] = r->sigma.zz, [MPM_SER_SXY] = r->sigma.xy,
    [MPM_SER_P] = p, [MPM_SER_TAU] = tau, [MPM_SER_MU] = p > 0.0 ? tau / p : 0.0,
    [MPM_SER_GDP] = r->gdp,
    [MPM_SER_DPXX] = Dp.xx, [MPM_SER_DPYY] = Dp.yy, [MPM_SER_DPZZ] = Dp.zz,
    [MPM_SER_DPXY] = Dp.xy, [MPM_SER_RHO] = r->rho, [MPM_SER_STATE] = r->state,
  };
  for (int f = 0; f < MPM_SER_N; f++)
    s->v[(size_t)f * s->n + k] = val[f];
}

/* ------------------------------------------------------- the discrete run */

size_t mpm_pointrun_steps(const mpm_history *h, double dt)
{
  double T = mpm_history_t_end(h) - mpm_history_t_begin(h);
  double q = T / dt, r = nearbyint(q);
  if (fabs(q - r) <= 1e-9 * (r > 1.0 ? r : 1.0))
    return r > 1.0 ? (size_t)r : 1;                            /* dt divides T */
  return (size_t)ceil(q);                                      /* last step shorter */
}

/* Time of row k of a run with nsteps steps of dt. */
static double row_time(const mpm_history *h, double dt, size_t k, size_t nsteps)
{
  return k == nsteps ? mpm_history_t_end(h) : mpm_history_t_begin(h) + (double)k * dt;
}

static mpm_mat3 sample_L(const mpm_history *h, double a, double b, int sample)
{
  switch (sample) {
  case MPM_SAMPLE_START: return mpm_history_eval(h, a);
  case MPM_SAMPLE_MID: return mpm_history_eval(h, 0.5 * (a + b));
  case MPM_SAMPLE_END: return mpm_history_eval(h, b);
  default: return mpm_history_mean(h, a, b);
  }
}

/* Initial state flag: dense iff rho >= rho_c and p > 0. */
int mpm_point_init_state(const mpm_material_params *par, const mpm_point_init *init)
{
  return init->rho >= par->rho_c && mpm_sym3_pressure(init->sigma) > 0.0
             ? MPM_STATE_DENSE : MPM_STATE_DISCONNECTED;
}

int mpm_pointrun_update(const mpm_material_type *mt, const mpm_material_params *par,
                        const mpm_history *h, const mpm_point_init *init, double dt,
                        int sample, mpm_series **out, mpm_err *err)
{
  *out = NULL;
  if (!(dt > 0.0) || !isfinite(dt))
    return mpm_err_set(err, MPM_EINVAL, "time step dt = %g: must be > 0", dt);
  size_t nsteps = mpm_pointrun_steps(h, dt);
  mpm_series *s = mpm_series_alloc(nsteps + 1);
  if (!s)
    return mpm_err_set(err, MPM_ENOMEM, "out of memory for %zu steps", nsteps);
  mpm_mpoint pt = {.sigma = init->sigma, .rho = init->rho};
  int st0 = mpm_point_init_state(par, init);
  mpm_mat3 L0 = mpm_history_eval(h, mpm_history_t_begin(h));
  mpm_sym3 D = mpm_mat3_sym(&L0);
  s->t[0] = mpm_history_t_begin(h);
  double gdp0 = mpm_material_mu_i_gdp(par, init->sigma, D, st0);
  mpm_series_record(s, 0, &(mpm_point_rec){init->sigma, init->rho, gdp0, st0, D});
  for (size_t k = 0; k < nsteps; k++) {
    double a = row_time(h, dt, k, nsteps), b = row_time(h, dt, k + 1, nsteps);
    mpm_mat3 L = sample_L(h, a, b, sample);
    pt.rho *= exp(-(b - a) * mpm_mat3_trace(&L));            /* rho_{k+1} */
    mt->update(par, &L, b - a, &pt);
    s->t[k + 1] = b;
    mpm_series_record(s, k + 1,
                      &(mpm_point_rec){pt.sigma, pt.rho, pt.gdp, pt.state, mpm_mat3_sym(&L)});
  }
  *out = s;
  return MPM_OK;
}

/* ------------------------------------------------------ norms and orders */

double mpm_series_relerr(const mpm_series *a, const mpm_series *ref, int field)
{
  double e2 = 0.0, r2 = 0.0;
  size_t n = a->n < ref->n ? a->n : ref->n;
  for (size_t k = 1; k < n; k++) {
    double w = ref->t[k] - ref->t[k - 1];                      /* step length */
    double r = mpm_series_at(ref, field, k), d = mpm_series_at(a, field, k) - r;
    e2 += w * d * d;
    r2 += w * r * r;
  }
  if (r2 == 0.0)
    return e2 == 0.0 ? 0.0 : INFINITY;
  return sqrt(e2 / r2);
}

double mpm_observed_order(const double *dt, const double *err, int n)
{
  double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  if (n < 2)
    return NAN;
  for (int i = 0; i < n; i++) {
    if (!(err[i] > 0.0 && isfinite(err[i]) && dt[i] > 0.0))
      return NAN;
    double x = log(dt[i]), y = log(err[i]);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
  }
  double den = n * sxx - sx * sx;                              /* n S_xx - S_x^2 */
  return den > 0.0 ? (n * sxy - sx * sy) / den : NAN;
}
