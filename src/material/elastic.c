/* elastic.c: linear elastic material in Jaumann hypoelastic form
 * (MODEL.md sections 1 and 4 step 2, without plasticity or disconnection):
 *   sigma_{n+1} = sigma_n + dt (C:D + W sigma_n - sigma_n W). */
#include "material/material.h"

#include <math.h>

#include "core/points.h"

int mpm_material_check_elastic(const mpm_material_params *par, mpm_err *err)
{
  if (!(par->E > 0.0 && isfinite(par->E)))
    return mpm_err_set(err, MPM_EINPUT, "key 'material.E' = %g: must be > 0 Pa", par->E);
  if (!(par->nu > -1.0 && par->nu < 0.5))
    return mpm_err_set(err, MPM_EINPUT, "key 'material.nu' = %g: allowed range (-1, 0.5)", par->nu);
  return MPM_OK;
}

/* One update of the point pt, by value: the kernel of update and update_point. */
MPM_MATERIAL_KERNEL mpm_mpoint elastic_step(const mpm_material_params *par, mpm_mat3 L, double dt,
                                            mpm_mpoint pt)
{
  mpm_sym3 D = mpm_mat3_sym(&L);
  pt.sigma = mpm_material_trial(par, D, &L, pt.sigma, dt);       /* no yield, no disconnection */
  pt.gdp = 0.0;
  pt.state = MPM_STATE_DENSE;
  return pt;
}

static void elastic_update_point(const mpm_material_params *par, const mpm_mat3 *L, double dt,
                                 mpm_mpoint *pt, mpm_mdeform *def)
{
  (void)def;   /* no deformation gradients */
  *pt = elastic_step(par, *L, dt, *pt);
}

/* A batch of points, the update above inlined. */
static void elastic_update(const mpm_material_params *par, double dt, int nsub,
                           const mpm_material_batch *b)
{
  mpm_material_loop(par, dt, nsub, b, elastic_step);
}

const mpm_material_type mpm_material_elastic = {
  .name = "elastic",
  .description = "linear elastic, Jaumann hypoelastic rate form",
  .check = mpm_material_check_elastic,
  .update = elastic_update,
  .update_point = elastic_update_point,
};
