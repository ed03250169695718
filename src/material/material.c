/* material.c: the material table, derived constants and shared checks
 * (MODEL.md section 1). */
#include "material/material.h"

#include "core/config.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

const mpm_material_type *const mpm_material_table[] = {
  &mpm_material_elastic,
  &mpm_material_mu_i,
  &mpm_material_ngf,
  &mpm_material_ngf_hyper,
  NULL
};

const mpm_material_type *mpm_material_lookup(const char *name)
{
  for (size_t i = 0; mpm_material_table[i]; i++)
    if (strcmp(mpm_material_table[i]->name, name) == 0)
      return mpm_material_table[i];
  return NULL;
}

void mpm_material_params_derive(mpm_material_params *par)
{
  par->G = par->E / (2.0 * (1.0 + par->nu));           /* G = E / 2(1+nu) */
  par->K = par->E / (3.0 * (1.0 - 2.0 * par->nu));     /* K = E / 3(1-2nu) */
  par->dmu = par->mu_2 - par->mu_s;                     /* Delta_mu */
  par->b = par->I0 > 0.0 ? par->dmu / par->I0 : 0.0;    /* b = Delta_mu / I0 */
  par->xi = (par->d > 0.0 && par->rho_s > 0.0)          /* xi = I0 / (d sqrt(rho_s)) */
                ? par->I0 / (par->d * sqrt(par->rho_s)) : 0.0;
}

void mpm_material_params_from_config(mpm_material_params *par, const mpm_config *cfg)
{
  memset(par, 0, sizeof *par);
  par->E = cfg->material.E;
  par->nu = cfg->material.nu;
  par->rho_s = cfg->material.rho_s;
  par->rho_c = cfg->material.rho_c;
  par->mu_s = cfg->material.mu_s;
  par->mu_2 = cfg->material.mu_2;
  par->I0 = cfg->material.I0;
  par->d = cfg->material.d;
  par->A = cfg->material.A;
  par->t0 = cfg->material.t0;
  par->form = cfg->material.form;
  par->p_sample = cfg->material.p_sample;
  par->t_seed = cfg->material.t_seed;
  mpm_material_params_derive(par);
}

void mpm_material_config_dk15(mpm_config *cfg)
{
  cfg->material.nu = MPM_DK15_NU;
  cfg->material.rho_s = MPM_DK15_RHO_S;
  cfg->material.rho_c = MPM_DK15_RHO_C;
  cfg->material.mu_s = MPM_DK15_MU_S;
  cfg->material.mu_2 = MPM_DK15_MU_2;
  cfg->material.I0 = MPM_DK15_I0;
  cfg->material.d = MPM_DK15_D;
}

double mpm_material_wave_speed(const mpm_material_params *par, double rho)
{
  return sqrt((par->K + 4.0 * par->G / 3.0) / rho);     /* c_p */
}

