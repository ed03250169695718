/* scenario.h: initial states of material points.
 *
 * Fill regions (rectangle, disc, polygon) with n x n points per mesh unit at a
 * given density and velocity; each point gets mass rho * V, true volume V =
 * dx dy / n^2 and a uGIMP extent r1 = (dx/2n, 0), r2 = (0, dy/2n). Optional
 * lithostatic pre-stress from the weight of the material above.
 *
 * 3D fills (fill3.c) of a box or a cylinder on a mesh of boxes (mpm_mesh3)
 * into a 3D point store: n x n x n points per unit, V = dx dy dz / n^3,
 * r1 = (dx/2n, 0, 0), r2 = (0, dy/2n, 0), r3 = (0, 0, dz/2n), zero stress. */
#ifndef MPM_SCENARIO_SCENARIO_H
#define MPM_SCENARIO_SCENARIO_H

#include <stddef.h>

#include "core/config.h"
#include "core/error.h"
#include "core/points.h"
#include "material/material.h"
#include "mesh/box.h"
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

/* ---- 3D ------------------------------------------------------------------ */

enum mpm_fill3_shape { MPM_FILL3_BOX = 0, MPM_FILL3_CYLINDER, MPM_FILL3_PRISM };

/* A region of a 3D fill and its material. */
typedef struct mpm_fill3_region {
  int shape;                   /* enum mpm_fill3_shape */
  double lo[3], hi[3];         /* box [lo_x, hi_x] x [lo_y, hi_y] x [lo_z, hi_z] [m];
                                  prism: the z range (lo[2], hi[2]) */
  const mpm_fill_config *polygon;  /* prism: the plane polygon (nvert, px, py) extruded
                                      along z; not owned */
  int axis;                    /* cylinder axis: 0 x, 1 y, 2 z */
  double centre[3];            /* cylinder centre: on the axis, mid-length [m] */
  double radius, length;       /* cylinder radius and extent along the axis [m] */
  int ppu;                     /* points per unit along each direction (n x n x n) */
  double density;              /* initial density [kg/m^3] */
  double v[3];                 /* initial velocity [m/s] */
} mpm_fill3_region;

/* 1 if x lies in the region (boundary included). */
int mpm_scenario_inside3(const mpm_fill3_region *f, const double x[3]);

/* Append the points of region f on m (set up) to the 3D store pts at the
 * sub-cell centres inside f, with zero stress. MPM_EINPUT for a 2D store, a
 * region that is not whole or leaves the mesh, or one with no centre in it. */
int mpm_scenario_fill3(mpm_points *pts, const mpm_mesh3 *m, const mpm_fill3_region *f,
                       mpm_err *err);

/* The pre-stress of fill f (lithostatic or pressure, as the plane fill:
 * sigma and the mass times exp(p/K)) on the points [first, pts->n) that
 * mpm_scenario_fill3 just appended on m, the sub-columns along x and z;
 * with hyper, also F = Fe of that stress (mpm_material_hyper_F_of_stress,
 * Fp = I). Nothing without a pre-stress. MPM_ENOMEM, MPM_EINPUT when no
 * elastic state carries the stress. */
int mpm_scenario_prestress3(mpm_points *pts, size_t first, const mpm_mesh3 *m,
                            const mpm_fill_config *f, const mpm_material_params *par, double gy,
                            int hyper, mpm_err *err);

/* The number of points mpm_scenario_fill3 appends for f on m (0 when it
 * would refuse f). */
size_t mpm_scenario_count3(const mpm_fill3_region *f, const mpm_mesh3 *m);

/* The 3D region of a fill section of a 3D input (mesh.nz > 0): a rectangle
 * extruded over [zmin, zmax] is a box, a disc a cylinder along z, a polygon
 * a prism along z (r->polygon points to f). */
void mpm_scenario_region3(const mpm_fill_config *f, mpm_fill3_region *r);

#endif
