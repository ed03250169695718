/* shape.h: shape-function variants and the per-point stencil (MODEL.md section 3).
 *
 * A variant is a const mpm_shape_type registered in mpm_shape_table (NULL
 * ended) and chosen by name in the input. It produces, for one point, the
 * nodes it touches with weights S_ip and gradients gradS_ip. The stencil holds
 * those for every point; the step computes it once and reuses it for
 * point-to-grid and grid-to-point. */
#ifndef MPM_SHAPE_SHAPE_H
#define MPM_SHAPE_SHAPE_H

#include <stddef.h>

#include "core/error.h"
#include "core/points.h"
#include "mesh/mesh.h"

/* Most nodes one point can touch (uGIMP: 4 corners x 4 nodes before merging). */
#define MPM_STENCIL_W 16

typedef struct mpm_shape_type {
  const char *name;
  const char *description;
  /* Weights of one point at (x, y) with extent half-vectors r1 = (r[0], r[1]),
   * r2 = (r[2], r[3]). Writes at most MPM_STENCIL_W distinct nodes; returns
   * their count, or -1 when the point lies outside the mesh. */
  int (*eval)(const mpm_mesh *m, double x, double y, const double r[4],
              int *node, double *S, double *dSx, double *dSy);
} mpm_shape_type;

extern const mpm_shape_type mpm_shape_delta;  /* S = N(x_p) */
extern const mpm_shape_type mpm_shape_ugimp;  /* CPDI corner rule, fixed extent */
extern const mpm_shape_type *const mpm_shape_table[];

/* Variant by name, NULL if unknown. */
const mpm_shape_type *mpm_shape_lookup(const char *name);

typedef struct mpm_shape_stencil {
  size_t cap;     /* points it has room for */
  int *count;     /* [cap] nodes per point */
  int *node;      /* [cap * MPM_STENCIL_W] storage node ids */
  double *S, *dSx, *dSy;  /* [cap * MPM_STENCIL_W] */
} mpm_shape_stencil;

mpm_shape_stencil *mpm_shape_stencil_alloc(size_t cap);
void mpm_shape_stencil_free(mpm_shape_stencil *st);  /* accepts NULL */

/* Stencil of every point (grows st as needed). A point outside the mesh is
 * MPM_EOUTSIDE with a message naming the point id, its position and time t. */
int mpm_shape_stencil_compute(mpm_shape_stencil *st, const mpm_shape_type *type, const mpm_mesh *m,
                              const mpm_points *pts, double t, mpm_err *err);

#endif
