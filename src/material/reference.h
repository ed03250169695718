/* reference.h: one material point driven by a velocity-gradient history:
 * time series of the discrete update, the ODE reference integrated with GSL's
 * rkf45, and the error norms and observed orders that compare them
 * (MODEL.md section 4, [DK15] App. B; verification case V2).
 *
 * Both series are sampled at the same times t_0 < t_1 < ... < t_N (the steps of
 * the discrete update). Row 0 is the initial state; row k > 0 is the state at
 * the end of step k. Quantities per row: the stress components, p, tau, mu,
 * gdot_p, the plastic strain rate Dp, density and state (enum mpm_point_state).
 * Conventions where p -> 0: mu = tau / p if p > 0, else 0; a disconnected point
 * has gdot_p = sqrt(2 D0:D0) and Dp = D0 (mu_i.c explains why). */
#ifndef MPM_MATERIAL_REFERENCE_H
#define MPM_MATERIAL_REFERENCE_H

#include <stddef.h>

#include "core/error.h"
#include "core/tensor3.h"
#include "material/history.h"
#include "material/material.h"

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
const char *mpm_series_name(int field);

typedef struct mpm_series {
  size_t n;     /* rows */
  double *t;    /* times [s] */
  double *v;    /* MPM_SER_N blocks of n values: field f of row k at v[f * n + k] */
} mpm_series;

mpm_series *mpm_series_alloc(size_t n);
void mpm_series_free(mpm_series *s);  /* accepts NULL */

static inline double mpm_series_at(const mpm_series *s, int field, size_t k)
{
  return s->v[(size_t)field * s->n + k];
}

/* Initial state of the point. */
typedef struct mpm_point_init {
  mpm_sym3 sigma;  /* initial stress [Pa] (in-plane components and zz) */
  double rho;      /* initial density [kg/m^3] */
} mpm_point_init;

/* Which L the discrete update uses for the step [t_k, t_k+1]. */
enum mpm_sample {
  MPM_SAMPLE_MEAN = 0,  /* (1/dt) int L dt: exact step mean (default) */
  MPM_SAMPLE_START,     /* L(t_k) */
  MPM_SAMPLE_MID,       /* L(t_k + dt/2) */
  MPM_SAMPLE_END        /* L(t_k+1) */
};

/* Sampling rule by name ("mean", "start", "mid", "end"); -1 if unknown. */
int mpm_sample_lookup(const char *name);

/* Number of steps of size dt over the history (the last one may be shorter). */
size_t mpm_pointrun_steps(const mpm_history *h, double dt);

/* The discrete update (model mt) over the whole history with step dt:
 * rho_{k+1} = rho_k exp(-dt tr L_k), then mt->update(L_k, dt) with that density. */
int mpm_pointrun_update(const mpm_material_type *mt, const mpm_material_params *par,
                        const mpm_history *h, const mpm_point_init *init, double dt,
                        int sample, mpm_series **out, mpm_err *err);

/* Reference ODE options. */
typedef struct mpm_reference_opts {
  double rtol;       /* relative tolerance (1e-10) */
  double atol;       /* absolute tolerance [Pa; kg/m^3] (1e-9) */
  double p_floor;    /* below this pressure the deviator is dropped [Pa] (1e-10 K) */
  unsigned long max_steps;  /* per output interval (1e7) */
} mpm_reference_opts;

/* Defaults above for the material par (p_floor scales with K). */
void mpm_reference_defaults(const mpm_material_params *par, mpm_reference_opts *o);

/* The mu(I) ODE of [DK15] eq. 2.15 with density as a state variable,
 *   dsigma/dt = C:(D - Dp(sigma)) + W sigma - sigma W,   drho/dt = -rho tr D,
 * integrated by gsl_odeiv2_step_rkf45 piecewise between the history's nodes and
 * evaluated at the times out->t[0 .. out->n-1] (filled by the caller, increasing,
 * inside the history). Disconnection as in the update: stress-free while
 * rho < rho_c or while p would become negative; a stress-free point reconnects
 * when rho >= rho_c and tr D < 0. Where 0 < p < p_floor the stress deviator
 * (bounded by mu_2 p) is taken as zero and Dp = D0, the p -> 0+ limit. */
int mpm_reference_run(const mpm_material_params *par, const mpm_history *h,
                      const mpm_point_init *init, const mpm_reference_opts *o,
                      mpm_series *out, mpm_err *err);

/* ---- shared by the runs (and the tests) */

/* State of the point at one time, as recorded. */
typedef struct mpm_point_rec {
  mpm_sym3 sigma;  /* stress [Pa] */
  double rho;      /* density [kg/m^3] */
  double gdp;      /* gdot_p [1/s] */
  int state;       /* enum mpm_point_state */
  mpm_sym3 D;      /* rate of deformation (gives Dp = D0 when disconnected) [1/s] */
} mpm_point_rec;

/* Fill row k of s from r (p, tau, mu and Dp derived as described above). */
void mpm_series_record(mpm_series *s, size_t k, const mpm_point_rec *r);

/* Initial state flag: dense iff rho >= rho_c and p > 0. */
int mpm_point_init_state(const mpm_material_params *par, const mpm_point_init *init);

/* Relative time-integrated L2 error of field f over rows 1 ... n-1 (each row
 * stands for its step, weight t_k - t_k-1):
 *   sqrt(sum w (a - r)^2) / sqrt(sum w r^2);  0 if both vanish, +inf if only r does. */
double mpm_series_relerr(const mpm_series *a, const mpm_series *ref, int field);

/* Least-squares slope of log(err) against log(dt) over n >= 2 points; NaN if
 * any error is not positive and finite. */
double mpm_observed_order(const double *dt, const double *err, int n);

#endif
