/* scenario_internal.h: pieces shared by the 2D and 3D fills of the scenario
 * module only (fill.c, fill3.c); not part of its interface. */
#ifndef MPM_SCENARIO_SCENARIO_INTERNAL_H
#define MPM_SCENARIO_SCENARIO_INTERNAL_H

#include "core/config.h"
#include "core/points.h"
#include "material/material.h"

/* Centre of sub-cell i (of n per unit of size d) along an axis from x0:
 * x0 + (i + 1/2) d / n. */
static inline double mpm_scenario_in_sub_centre(double x0, double d, int n, long i)
{
  return x0 + ((double)i + 0.5) * (d / n);
}

/* The pre-stress of fill f ([DK-silo] 7.1 lithostatic, [D-thesis] ch. 4
 * isotropic; fill.c's header) on the points [first, pts->n) just appended:
 * sigma_yy = rho gy (y_top - y), y_top the highest point of the same
 * sub-column plus half a sub-cell, sigma_xx = sigma_zz = K0 sigma_yy, or
 * sigma = -p I; each point's mass times exp(p/K). Sub-columns of width h[0]
 * along x from o[0] (nc[0] of them) and, in a 3D store, h[2] along z from
 * o[1] (nc[1]); h[1] the sub-cell height. Nothing without a pre-stress;
 * MPM_ENOMEM. */
int mpm_scenario_in_prestress(mpm_points *pts, size_t first, const mpm_fill_config *f,
                              const mpm_material_params *par, double gy, const double o[2],
                              const double h[3], const long nc[2]);

#endif
