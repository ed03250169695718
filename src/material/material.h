/* material.h: constitutive models behind one interface (MODEL.md sections 4-5).
 *
 * A model is a const mpm_material_type in mpm_material_table (NULL ended),
 * chosen by its name in the input. Its parameters live in mpm_material_params
 * (filled from the input, derived constants by mpm_material_params_derive);
 * nothing is global. The update advances the stress of one point over dt with
 * the velocity gradient L fixed, given the new density pt->rho. */
#ifndef MPM_MATERIAL_MATERIAL_H
#define MPM_MATERIAL_MATERIAL_H

#include "core/error.h"
#include "core/tensor3.h"

typedef struct mpm_material_params {
  /* from the input */
  double E, nu;          /* Young's modulus [Pa], Poisson ratio */
  double rho_s, rho_c;   /* grain density, critical (disconnection) density [kg/m^3] */
  double mu_s, mu_2, I0; /* mu(I): static and limit friction, I0 */
  double d;              /* grain diameter [m] */
  double A, t0;          /* NGF amplitude and time scale [s] */
  /* derived (mpm_material_params_derive) */
  double G, K;           /* shear and bulk modulus [Pa] */
  double dmu;            /* mu_2 - mu_s */
  double b;              /* dmu / I0 */
  double xi;             /* I0 / (d sqrt(rho_s)) [sqrt(m/kg)] */
} mpm_material_params;

/* Fill G, K, dmu, b, xi from the input values. */
void mpm_material_params_derive(mpm_material_params *par);

/* Constitutive state of one point, gathered from the point store. */
typedef struct mpm_mpoint {
  mpm_sym3 sigma;  /* Cauchy stress [Pa], in: sigma_n, out: sigma_{n+1} */
  double rho;      /* density rho_{n+1} [kg/m^3] (input) */
  double g;        /* fluidity [1/s] */
  double gdp;      /* equivalent plastic shear rate [1/s] (output) */
  int state;       /* enum mpm_point_state (output) */
} mpm_mpoint;

typedef struct mpm_material_type {
  const char *name;
  const char *description;
  /* Check the parameters this model uses (ranges); message names the key. */
  int (*check)(const mpm_material_params *par, mpm_err *err);
  /* sigma_n -> sigma_{n+1} over dt with L fixed. Never fails: physical limits
   * (p -> 0, disconnection) are states, not errors. */
  void (*update)(const mpm_material_params *par, const mpm_mat3 *L, double dt,
                 mpm_mpoint *pt);
} mpm_material_type;

extern const mpm_material_type mpm_material_elastic;  /* Jaumann hypoelastic */
extern const mpm_material_type mpm_material_mu_i;     /* trans-phase mu(I) [DK15] */
extern const mpm_material_type *const mpm_material_table[];

/* Model by name, NULL if unknown. */
/* Shared parameter checks for models (message names the key and range). */
int mpm_material_check_elastic(const mpm_material_params *par, mpm_err *err);

const mpm_material_type *mpm_material_lookup(const char *name);

/* P-wave speed sqrt((K + 4G/3) / rho) for the time-step limit. */
double mpm_material_wave_speed(const mpm_material_params *par, double rho);

#endif
