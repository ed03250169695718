/* shape3.h: shape-function variants on the 3D mesh of boxes (box.h), for the
 * 3D module (MODEL.md sections 3 and 7).
 *
 * The 3D counterpart of shape.h's registry: a variant is a const
 * mpm_shape3_type in mpm_shape3_table (NULL ended), found by name. It gives
 * one point's nodes with weights S_ip and gradients gradS_ip on the
 * trilinear (Q8) basis:
 *   delta  S_ip = N_i(x_p), gradS_ip = grad N_i(x_p);
 *   ugimp  the CPDI corner rule on the parallelepiped of half-vectors r1, r2,
 *          r3 (8 corners, corners.h), the extent fixed as filled;
 *   cpdi   CPDI1: the same rule, the extent convected by the deformation
 *          (mpm_shape_extent_convect_dim with D = 3).
 * mpm_shape3_stencil_compute stores them for every point of a 3D store, in
 * the stencil of shape.h. */
#ifndef MPM_SHAPE_SHAPE3_H
#define MPM_SHAPE_SHAPE3_H

#include <stddef.h>

#include "mesh/box.h"
#include "shape/shape.h"

/* Most nodes one point can touch (the corner rule: 8 corners x 8 nodes
 * before merging; extents up to half a unit touch at most 3 x 3 x 3). */
#define MPM_STENCIL3_W 64

typedef struct mpm_shape3_type {
  const char *name;
  const char *description;
  /* Weights of one point at x with extent half-vectors r_k = (r[3k],
   * r[3k + 1], r[3k + 2]), k = 0, 1, 2 (either orientation). Writes at most
   * MPM_STENCIL3_W distinct nodes and returns their count; -1 when the point
   * lies outside a non-periodic face, or x or the extent is not finite (or
   * its corner geometry overflows). */
  int (*eval)(const mpm_mesh3 *m, const double x[3], const double r[9], int *node,
              double *S, double *dSx, double *dSy, double *dSz);
  /* For n points of extents r[9 p .. 9 p + 8]: *width, the most nodes eval
   * gives one of them (<= MPM_STENCIL3_W), and *reach, how many units beyond
   * its own along any axis its nodes go: a point in unit i touches nodes
   * i - reach .. i + 1 + reach along each axis. */
  void (*span)(const mpm_mesh3 *m, size_t n, const double *r, int *width, int *reach);
  /* 1 if the weights are the element basis at the point (S = N(x_p)) */
  int at_point;
  /* 1 if the extent follows the deformation (CPDI1) */
  int convect;
} mpm_shape3_type;

extern const mpm_shape3_type mpm_shape3_delta;  /* S = N(x_p) */
extern const mpm_shape3_type mpm_shape3_ugimp;  /* corner rule, fixed extent */
extern const mpm_shape3_type mpm_shape3_cpdi;   /* corner rule, convected extent (CPDI1) */
extern const mpm_shape3_type *const mpm_shape3_table[];

/* Variant by name, NULL if unknown. */
const mpm_shape3_type *mpm_shape3_lookup(const char *name);

/* The stencil of every point of the 3D store pts (grows st; w the largest
 * width the shape's span gives one of the points, reach the largest reach;
 * row[p] the unit layer along z of the point's centre). A point outside a
 * non-periodic face, or with a non-finite position or extent, is
 * MPM_EOUTSIDE naming the point, its position and time t. */
int mpm_shape3_stencil_compute(mpm_shape_stencil *st, const mpm_shape3_type *type,
                               const mpm_mesh3 *m, const mpm_points *pts, double t,
                               mpm_err *err);

#endif
