/* sim_config.h: pieces of hand-built run configurations shared by the tests
 * that drive mpm_sim directly (test_solver, test_threads, test_silo). */
#ifndef MPM_TESTS_SIM_CONFIG_H
#define MPM_TESTS_SIM_CONFIG_H

#include <string.h>

#include "core/config.h"
#include "material/material.h"

/* An empty configuration: all zero, except what zero would switch on (the
 * absorbing layer: above y = 0 would cover the whole mesh). */
static inline void sim_config_clear(mpm_config *c)
{
  memset(c, 0, sizeof *c);
  c->absorb.above = 1e9;
}

/* Material of the given model with the [DK15] Table 1 values (nu = 0.3,
 * mu_s = 0.3819, mu_2 = 0.6435, I0 = 0.279, d = 5 mm, rho_s = 2450,
 * rho_c = 1500) and NGF t0 = 1 ms; E is the test's own (small, for large
 * steps). */
static inline void sim_config_material(mpm_config *c, const char *model, double E)
{
  strcpy(c->material.model, model);
  mpm_material_config_dk15(c);
  c->material.E = E;
  c->material.t0 = 1e-3;
}

#endif
