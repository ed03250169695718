/* material.c: the material table, derived constants and shared checks
 * (MODEL.md section 1). */
#include "material/material.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

const mpm_material_type *const mpm_material_table[] = {
  &mpm_material_elastic,
  &mpm_material_mu_i,
  &mpm_material_ngf,
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

double mpm_material_wave_speed(const mpm_material_params *par, double rho)
{
  return sqrt((par->K + 4.0 * par->G / 3.0) / rho);     /* c_p */
}

int mpm_material_check_elastic(const mpm_material_params *par, mpm_err *err)
{
  if (!(par->E > 0.0 && isfinite(par->E)))
    return mpm_err_set(err, MPM_EINPUT, "key 'material.E' = %g: must be > 0 Pa", par->E);
  if (!(par->nu > -1.0 && par->nu < 0.5))
    return mpm_err_set(err, MPM_EINPUT, "key 'material.nu' = %g: allowed range (-1, 0.5)", par->nu);
  return MPM_OK;
}
