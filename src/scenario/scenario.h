/* scenario.h: initial states of material points, on a mesh of either
 * dimension.
 *
 * Fill regions with n points per unit along each axis (n x n in the plane,
 * n x n x n on boxes) at a given density and velocity: in the plane a
 * rectangle, a disc or a polygon; in 3D the box of a rectangle and the fill's
 * z range, a cylinder (a disc along z, or along x or y: the fill's axis) or
 * the prism along z of a polygon. Each point gets mass rho V, true volume
 * V = dx dy (dz) / n^D and a uGIMP extent r_d = (h_d / 2n) e_d. Optional
 * lithostatic or isotropic pre-stress; a model that carries deformation
 * gradients gets F = Fe of that stress, Fp = I. */
#ifndef MPM_SCENARIO_SCENARIO_H
#define MPM_SCENARIO_SCENARIO_H

#include <stddef.h>

#include "core/config.h"
#include "core/error.h"
#include "core/points.h"
#include "material/material.h"
#include "mesh/mesh.h"

/* Append the points of one fill region on m (the store's dimension is the
 * mesh's); gy is the final vertical gravity used by a lithostatic
 * pre-stress (negative downwards). MPM_EINPUT for a store of another
 * dimension, a bad ppu or density, a region that leaves the mesh (its
 * points outside would be lost) or holds no point centre; MPM_ENOMEM. */
int mpm_scenario_fill(mpm_points *pts, const mpm_mesh *m, const mpm_fill_config *f,
                      const mpm_material_params *par, double gy, mpm_err *err);

/* The number of points mpm_scenario_fill appends for f on m, exactly, and
 * without making them (a few bisections per row of sub-cells): for the size
 * of a run before it is built. */
size_t mpm_scenario_count(const mpm_fill_config *f, const mpm_mesh *m);

/* 1 if x (x[2] unread in the plane) lies in the region of f in dim
 * dimensions (boundary included). */
int mpm_scenario_inside(const mpm_fill_config *f, int dim, const double x[3]);

#endif
