/* reference.h: the mu(I) constitutive ODE of one material point driven by a
 * velocity-gradient history, integrated with GSL's rkf45 at tight tolerance:
 * the reference the discrete update (pointrun.h) is compared with
 * (MODEL.md section 4, [DK15] App. B; verification case V2). */
#ifndef MPM_POINTRUN_REFERENCE_H
#define MPM_POINTRUN_REFERENCE_H

#include "core/error.h"
#include "material/material.h"
#include "pointrun/history.h"
#include "pointrun/pointrun.h"
#include "pointrun/series.h"

/* Reference ODE options. */
typedef struct mpm_reference_opts {
  double rtol;       /* relative tolerance (1e-10) */
  double atol;       /* absolute tolerance [Pa; kg/m^3] (1e-9) */
  double p_floor;    /* below this pressure the deviator is dropped [Pa] (1e-10 K) */
  unsigned long max_steps;  /* per output interval (1e7) */
} mpm_reference_opts;

/* Defaults above for the material par (p_floor scales with K). */
void mpm_pointrun_reference_defaults(const mpm_material_params *par, mpm_reference_opts *o);

/* The mu(I) ODE of [DK15] eq. 2.15 with density as a state variable,
 *   dsigma/dt = C:(D - Dp(sigma)) + W sigma - sigma W,   drho/dt = -rho tr D,
 * integrated by gsl_odeiv2_step_rkf45 piecewise between the history's nodes and
 * evaluated at the times out->t[0 .. out->n-1] (filled by the caller, increasing,
 * inside the history). Disconnection as in the update: stress-free while
 * rho < rho_c or while p would become negative; a stress-free point reconnects
 * when rho >= rho_c and tr D < 0. Where 0 < p < p_floor the stress deviator
 * (bounded by mu_2 p) is taken as zero and Dp = D0, the p -> 0+ limit. */
int mpm_pointrun_reference_run(const mpm_material_params *par, const mpm_history *h,
                               const mpm_point_init *init, const mpm_reference_opts *o,
                               mpm_series *out, mpm_err *err);

#endif
