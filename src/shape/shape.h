/* shape.h: shape-function variants and the per-point stencil (MODEL.md section 3).
 *
 * A variant is a const mpm_shape_type registered in mpm_shape_table (NULL
 * ended) and chosen by name in the input. It produces, for one point, the
 * nodes it touches with weights S_ip and gradients gradS_ip. The stencil holds
 * those for every point, at the width the shape needs for them; the step
 * computes it once and reuses it for point-to-grid and grid-to-point (or,
 * for a shape whose weights are the element basis at the point, evaluates
 * them where it needs them). */
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
  /* For the points pts on mesh m: *width, the most nodes eval gives one of
   * them (<= MPM_STENCIL_W), and *reach, how many unit rows (and columns)
   * beyond its own unit its nodes go: a point in unit row j touches node rows
   * j - reach .. j + 1 + reach. */
  void (*span)(const mpm_mesh *m, const mpm_points *pts, int *width, int *reach);
  /* 1 if the weights are the element basis at the point itself (S = N(x_p)):
   * the step then evaluates them from the located point (mpm_mesh_basis_at)
   * where it needs them instead of storing a stencil. */
  int at_point;
  /* 1 if the extent follows the deformation (CPDI1): every step moves the
   * half-vectors with the point's velocity gradient
   * (mpm_shape_extent_convect); 0: the extent stays as filled. */
  int convect;
} mpm_shape_type;

/* CPDI1: the extent half-vectors r = (r1x, r1y, r2x, r2y) carried over dt by
 * the velocity gradient L = (dvx/dx, dvx/dy, dvy/dx, dvy/dy) of the point,
 * r_k <- (I + dt L) r_k, as the deformation gradient F_{n+1} = (I + dt L) F_n
 * carries the filled extent r_k = F r_k0 (MODEL.md section 3). */
static inline void mpm_shape_extent_convect(double *r1x, double *r1y, double *r2x, double *r2y,
                                            double lxx, double lxy, double lyx, double lyy,
                                            double dt)
{
  const double ax = *r1x, ay = *r1y, bx = *r2x, by = *r2y;
  *r1x = ax + dt * (lxx * ax + lxy * ay);
  *r1y = ay + dt * (lyx * ax + lyy * ay);
  *r2x = bx + dt * (lxx * bx + lxy * by);
  *r2y = by + dt * (lyx * bx + lyy * by);
}

extern const mpm_shape_type mpm_shape_delta;  /* S = N(x_p) */
extern const mpm_shape_type mpm_shape_ugimp;  /* CPDI corner rule, fixed extent */
extern const mpm_shape_type mpm_shape_cpdi;   /* CPDI corner rule, convected extent (CPDI1) */
extern const mpm_shape_type *const mpm_shape_table[];

/* Variant by name, NULL if unknown. */
const mpm_shape_type *mpm_shape_lookup(const char *name);

/* Point p's nodes are node[p w .. p w + count[p]), their weights and
 * gradients at the same places of S, dSx, dSy: w is the width of the shape
 * for the points (span), so a stencil takes w (4 + 3 x 8) bytes a point. */
typedef struct mpm_shape_stencil {
  size_t cap;     /* points it has room for, at width w */
  int w;          /* slots per point */
  int reach;      /* node rows beyond a point's unit row (span) */
  int *count;     /* [cap] nodes per point */
  int *row;       /* [cap] unit row of each point's centre */
  int *node;      /* [cap * w] storage node ids */
  double *S, *dSx, *dSy;  /* [cap * w] */
  size_t wcap;    /* room in node, S, dSx, dSy (entries) */
} mpm_shape_stencil;

mpm_shape_stencil *mpm_shape_stencil_alloc(size_t cap);
void mpm_shape_stencil_free(mpm_shape_stencil *st);  /* accepts NULL */

/* Stencil of every point (grows st as needed; sets w and reach from the
 * shape's span). A point outside the mesh is MPM_EOUTSIDE with a message
 * naming the point id, its position and time t. */
int mpm_shape_stencil_compute(mpm_shape_stencil *st, const mpm_shape_type *type, const mpm_mesh *m,
                              const mpm_points *pts, double t, mpm_err *err);

#endif
