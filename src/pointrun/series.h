/* series.h: the time series recorded while one material point is driven by a
 * velocity-gradient history, and the norms that compare two of them
 * (MODEL.md section 4, [DK15] App. B; verification case V2).
 *
 * The discrete update (pointrun.h) and the ODE reference (reference.h) fill
 * series at the same times t_0 < t_1 < ... < t_N (the steps of the update).
 * Row 0 is the initial state; row k > 0 is the state at the end of step k.
 * Quantities per row: the stress components, p, tau, mu, gdot_p, the plastic
 * strain rate Dp, density and state (enum mpm_point_state).
 * Conventions where p -> 0: mu = tau / p if p > 0, else 0; a disconnected point
 * has gdot_p = sqrt(2 D0:D0) and Dp = D0 (mu_i.c explains why). */
#ifndef MPM_POINTRUN_SERIES_H
#define MPM_POINTRUN_SERIES_H

#include <stddef.h>

#include "core/tensor3.h"

/* Recorded quantities: X(enum, column name). */
#define MPM_SERIES_FIELDS(X)  \
  X(MPM_SER_SXX, "sxx")       \
  X(MPM_SER_SYY, "syy")       \
  X(MPM_SER_SZZ, "szz")       \
  X(MPM_SER_SXY, "sxy")       \
  X(MPM_SER_P, "p")           \
  X(MPM_SER_TAU, "tau")       \
  X(MPM_SER_MU, "mu")         \
  X(MPM_SER_GDP, "gdot_p")    \
  X(MPM_SER_DPXX, "dp_xx")    \
  X(MPM_SER_DPYY, "dp_yy")    \
  X(MPM_SER_DPZZ, "dp_zz")    \
  X(MPM_SER_DPXY, "dp_xy")    \
  X(MPM_SER_RHO, "rho")       \
  X(MPM_SER_STATE, "state")

#define MPM_SERIES_ENUM_(e, name) e,
enum mpm_series_field { MPM_SERIES_FIELDS(MPM_SERIES_ENUM_) MPM_SER_N };
#undef MPM_SERIES_ENUM_

/* Column name of a field ("sxx", ..., "state"); NULL if out of range. */
const char *mpm_pointrun_series_name(int field);

typedef struct mpm_series {
  size_t n;     /* rows */
  double *t;    /* times [s] */
  double *v;    /* MPM_SER_N blocks of n values: field f of row k at v[f * n + k] */
} mpm_series;

mpm_series *mpm_pointrun_series_alloc(size_t n);
void mpm_pointrun_series_free(mpm_series *s);  /* accepts NULL */

static inline double mpm_pointrun_series_at(const mpm_series *s, int field, size_t k)
{
  return s->v[(size_t)field * s->n + k];
}

/* State of the point at one time, as recorded. */
typedef struct mpm_point_rec {
  mpm_sym3 sigma;  /* stress [Pa] */
  double rho;      /* density [kg/m^3] */
  double gdp;      /* gdot_p [1/s] */
  int state;       /* enum mpm_point_state */
  mpm_sym3 D;      /* rate of deformation (gives Dp = D0 when disconnected) [1/s] */
} mpm_point_rec;

/* Fill row k of s from r (p, tau, mu and Dp derived as described above). */
void mpm_pointrun_series_record(mpm_series *s, size_t k, const mpm_point_rec *r);

/* Relative time-integrated L2 error of field f over rows 1 ... n-1 (each row
 * stands for its step, weight t_k - t_k-1):
 *   sqrt(sum w (a - r)^2) / sqrt(sum w r^2);  0 if both vanish, +inf if only r does. */
double mpm_pointrun_series_relerr(const mpm_series *a, const mpm_series *ref, int field);

/* Observed order of convergence: least-squares slope of log(err) against
 * log(dt) over n >= 2 points; NaN if any error is not positive and finite. */
double mpm_pointrun_order(const double *dt, const double *err, int n);

#endif
