/* scenario_internal.h: pieces shared by the 2D and 3D fills of the scenario
 * module only (fill.c, fill3.c); not part of its interface. */
#ifndef MPM_SCENARIO_SCENARIO_INTERNAL_H
#define MPM_SCENARIO_SCENARIO_INTERNAL_H

/* Centre of sub-cell i (of n per unit of size d) along an axis from x0:
 * x0 + (i + 1/2) d / n. */
static inline double mpm_scenario_in_sub_centre(double x0, double d, int n, long i)
{
  return x0 + ((double)i + 0.5) * (d / n);
}

#endif
