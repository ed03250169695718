/* pointrun.h: one material point driven by a velocity-gradient history with a
 * model's own stress update, step by step (MODEL.md section 4, [DK15] App. B;
 * verification case V2). The module: history.h (the prescribed L(t)),
 * series.h (what is recorded, error norms and orders), this file (the
 * discrete run) and reference.h (the mu(I) ODE integrated with GSL's rkf45). */
#ifndef MPM_POINTRUN_POINTRUN_H
#define MPM_POINTRUN_POINTRUN_H

#include <stddef.h>

#include "core/error.h"
#include "core/tensor3.h"
#include "material/material.h"
#include "pointrun/history.h"
#include "pointrun/series.h"

/* Initial state of the point. */
typedef struct mpm_point_init {
  mpm_sym3 sigma;  /* initial stress [Pa] (in-plane components and zz) */
  double rho;      /* initial density [kg/m^3] */
} mpm_point_init;

/* Initial state flag (enum mpm_point_state): dense iff rho >= rho_c and p > 0. */
int mpm_pointrun_init_state(const mpm_material_params *par, const mpm_point_init *init);

/* Which L the discrete update uses for the step [t_k, t_k+1]. */
enum mpm_sample {
  MPM_SAMPLE_MEAN = 0,  /* (1/dt) int L dt: exact step mean (default) */
  MPM_SAMPLE_START,     /* L(t_k) */
  MPM_SAMPLE_MID,       /* L(t_k + dt/2) */
  MPM_SAMPLE_END        /* L(t_k+1) */
};

/* Sampling rule by name ("mean", "start", "mid", "end"); -1 if unknown. */
int mpm_pointrun_sample_from_name(const char *name);

/* Number of steps of size dt over the history (the last one may be shorter). */
size_t mpm_pointrun_steps(const mpm_history *h, double dt);

/* The discrete update (model mt) over the whole history with step dt:
 * rho_{k+1} = rho_k exp(-dt tr L_k), then mt->update(L_k, dt) with that density. */
int mpm_pointrun_update(const mpm_material_type *mt, const mpm_material_params *par,
                        const mpm_history *h, const mpm_point_init *init, double dt,
                        int sample, mpm_series **out, mpm_err *err);

#endif
