/* sim_config.h: pieces of hand-built run configurations shared by the tests
 * that drive mpm_sim directly (test_solver, test_solver_box, test_threads,
 * test_silo). */
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

/* An elastic box of nx x ny x nz units of 1 cm (nz = 0: the plane) filled
 * with 2 x 2 (x 2) points a unit, cfl 0.5, FLIP; faces periodic unless set
 * otherwise by the caller. */
static inline void sim_config_box(mpm_config *c, const char *shape, int nx, int ny, int nz)
{
  sim_config_clear(c);
  c->mesh.nx = nx;
  c->mesh.ny = ny;
  c->mesh.nz = nz;
  c->mesh.dx = c->mesh.dy = c->mesh.dz = 0.01;
  strcpy(c->mesh.topology, "q4");
  strcpy(c->mesh.diagonal, "/");
  strcpy(c->mesh.shape, shape);
  c->time.cfl = 0.5;
  c->time.t_end = 1.0;
  c->time.frame_dt = 1.0;
  c->time.flip = 1.0;
  sim_config_material(c, "elastic", 1e6);
  c->bc.left = c->bc.right = c->bc.bottom = c->bc.top = MPM_BC_PERIODIC;
  c->bc.front = c->bc.back = MPM_BC_PERIODIC;
  c->nfill = 1;
  mpm_fill_config *f = &c->fill[0];
  f->shape = MPM_FILL_RECTANGLE;
  f->xmax = 0.01 * nx;
  f->ymax = 0.01 * ny;
  f->zmax = 0.01 * nz;
  f->ppu = 2;
  f->density = 1500;
  strcpy(f->name, "box");
}

/* A column 5 x 6 cm collapsing under gravity onto a rough floor between a
 * symmetry plane (left) and a frictionless wall (right) 12 cm away, in a
 * mesh 8 cm high, periodic in z over nz units (nz = 0: its plane
 * counterpart), of the given model. */
static inline void sim_config_column(mpm_config *c, const char *shape, int nz, const char *model)
{
  sim_config_box(c, shape, 12, 8, nz);
  sim_config_material(c, model, 1e6);
  c->bc.left = MPM_BC_SYMMETRY;
  c->bc.right = MPM_BC_FRICTIONLESS;
  c->bc.bottom = MPM_BC_NOSLIP;
  c->bc.top = MPM_BC_FREE;
  if (nz == 0)
    c->bc.front = c->bc.back = MPM_BC_FREE;
  c->gravity.gy = -9.8;
  c->fill[0].xmax = 0.05;
  c->fill[0].ymax = 0.06;
}

#endif
