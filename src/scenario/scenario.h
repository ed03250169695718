/* scenario.h: initial states of material points.
 *
 * Fill regions (rectangle, disc, polygon) with n x n points per mesh unit at a
 * given density and velocity; each point gets mass rho * V, true volume V =
 * dx dy / n^2 and a uGIMP extent r1 = (dx/2n, 0), r2 = (0, dy/2n). Optional
 * lithostatic pre-stress from the weight of the material above. */
#ifndef MPM_SCENARIO_SCENARIO_H
#define MPM_SCENARIO_SCENARIO_H

#include <stddef.h>

#include "core/config.h"
#include "core/error.h"
#include "core/points.h"
#include "material/material.h"
#include "mesh/mesh.h"

/* Append the points of one fill region; gy is the final vertical gravity used
 * by a lithostatic pre-stress (negative downwards). */
int mpm_scenario_fill(mpm_points *pts, const mpm_mesh *m, const mpm_fill_config *f,
                      const mpm_material_params *par, double gy, mpm_err *err);

/* The number of points mpm_scenario_fill appends for f on m, exactly, and
 * without making them (a few bisections per row of sub-cells): for the size
 * of a run before it is built. */
size_t mpm_scenario_count(const mpm_fill_config *f, const mpm_mesh *m);

/* 1 if (x, y) lies in the region. */
int mpm_scenario_inside(const mpm_fill_config *f, double x, double y);

#endif
