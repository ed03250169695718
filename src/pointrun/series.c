/* series.c: the time series of one driven material point: recording a state,
 * the relative error of one series against another and the observed order
 * (series.h; MODEL.md section 4).
 *
 * Recorded: p = -tr(sigma)/3, tau = sqrt(sigma0:sigma0/2), mu = tau/p (0 if p <= 0),
 *   Dp = gdot_p sigma0 / (2 tau) if tau > 0, else gdot_p D0 / sqrt(2 D0:D0)
 *   (stress-free: Dp = D0 since gdot_p = sqrt(2 D0:D0) there).
 * Error: e_f = sqrt(sum_k w_k (a_k - r_k)^2) / sqrt(sum_k w_k r_k^2), w_k = t_k - t_{k-1};
 * order: least-squares slope of log e against log dt. */
#include "pointrun/series.h"

#include <math.h>
#include <stdlib.h>

#define MPM_SERIES_NAME_(e, name) name,
static const char *const series_names[MPM_SER_N] = {MPM_SERIES_FIELDS(MPM_SERIES_NAME_)};
#undef MPM_SERIES_NAME_

const char *mpm_pointrun_series_name(int field)
{
  return field >= 0 && field < MPM_SER_N ? series_names[field] : NULL;
}

mpm_series *mpm_pointrun_series_alloc(size_t n)
{
  mpm_series *s = calloc(1, sizeof *s);
  if (!s)
    return NULL;
  s->n = n;
  s->t = calloc(n ? n : 1, sizeof *s->t);
  s->v = calloc((n ? n : 1) * MPM_SER_N, sizeof *s->v);
  if (!s->t || !s->v) {
    mpm_pointrun_series_free(s);
    return NULL;
  }
  return s;
}

void mpm_pointrun_series_free(mpm_series *s)
{
  if (!s)
    return;
  free(s->t);
  free(s->v);
  free(s);
}

/* ------------------------------------------------------------ recording */

void mpm_pointrun_series_record(mpm_series *s, size_t k, const mpm_point_rec *r)
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

/* ------------------------------------------------------ norms and orders */

double mpm_pointrun_series_relerr(const mpm_series *a, const mpm_series *ref, int field)
{
  double e2 = 0.0, r2 = 0.0;
  size_t n = a->n < ref->n ? a->n : ref->n;
  for (size_t k = 1; k < n; k++) {
    double w = ref->t[k] - ref->t[k - 1];                      /* step length */
    double r = mpm_pointrun_series_at(ref, field, k);
    double d = mpm_pointrun_series_at(a, field, k) - r;
    e2 += w * d * d;
    r2 += w * r * r;
  }
  if (r2 == 0.0)
    return e2 == 0.0 ? 0.0 : INFINITY;
  return sqrt(e2 / r2);
}

double mpm_pointrun_order(const double *dt, const double *err, int n)
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
