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

struct mpm_shape_stencil;

typedef struct mpm_shape_type {
  const char *name;
  const char *description;
  /* Weights of one point at (x, y) with extent half-vectors r1 = (r[0], r[1]),
   * r2 = (r[2], r[3]). Writes at most MPM_STENCIL_W distinct nodes (one may
   * have weights 0: a node of the units the point reaches that it does not
   * weigh); returns their count, or -1 when the point lies outside the
   * mesh. */
  int (*eval)(const mpm_mesh *m, double x, double y, const double r[4],
              int *node, double *S, double *dSx, double *dSy);
  /* Optional, the same for the points [lo, hi) at once, in a loop the
   * shape can specialise: for each point p the weights in its slots of the
   * stencil st (sized for the points at width st->w), and count[p] and
   * row[p] (mpm_shape_stencil_point); returns the first point outside the
   * mesh, or hi. NULL: eval, point by point. */
  long (*fill)(const mpm_mesh *m, const mpm_points *pts, long lo, long hi,
               struct mpm_shape_stencil *st);
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

/* CPDI1 in D = 2 or 3 dimensions: the extent half-vectors r_k
 * (r[D k + d] = component d of r_{k+1}) carried over dt by the velocity
 * gradient L of the point (L[D a + b] = dv_a/dx_b),
 *   r_k <- (I + dt L) r_k = r_k + dt (L r_k),
 * as the deformation gradient F_{n+1} = (I + dt L) F_n carries the filled
 * extent r_k = F r_k0 (MODEL.md section 3). (L r_k)_a sums over b in b order
 * from its first term. */
static inline void mpm_shape_extent_convect_dim(int D, double *r, const double *L, double dt)
{
  for (int k = 0; k < D; k++) {
    double a[3];
    for (int d = 0; d < D; d++)
      a[d] = r[D * k + d];
    for (int d = 0; d < D; d++) {
      double t = L[D * d] * a[0];
      for (int b = 1; b < D; b++)
        t += L[D * d + b] * a[b];
      r[D * k + d] = a[d] + dt * t;
    }
  }
}

/* The same in 2D on the fields of a plane-strain point, r1 = (r1x, r1y),
 * r2 = (r2x, r2y), L = (dvx/dx, dvx/dy, dvy/dx, dvy/dy) = (lxx, lxy, lyx, lyy):
 * r1x <- r1x + dt (lxx r1x + lxy r1y), and so on. */
static inline void mpm_shape_extent_convect(double *r1x, double *r1y, double *r2x, double *r2y,
                                            double lxx, double lxy, double lyx, double lyy,
                                            double dt)
{
  double r[4] = {*r1x, *r1y, *r2x, *r2y};
  const double L[4] = {lxx, lxy, lyx, lyy};
  mpm_shape_extent_convect_dim(2, r, L, dt);
  *r1x = r[0];
  *r1y = r[1];
  *r2x = r[2];
  *r2y = r[3];
}

extern const mpm_shape_type mpm_shape_delta;  /* S = N(x_p) */
extern const mpm_shape_type mpm_shape_ugimp;  /* CPDI corner rule, fixed extent */
extern const mpm_shape_type mpm_shape_cpdi;   /* CPDI corner rule, convected extent (CPDI1) */
extern const mpm_shape_type *const mpm_shape_table[];

/* Variant by name, NULL if unknown. */
const mpm_shape_type *mpm_shape_lookup(const char *name);

/* Point p's nodes are node[p w .. p w + count[p]), their weights and
 * gradients at the same places of S, dSx, dSy (and dSz on a 3D mesh, NULL
 * on a plane one): w is the width of the shape for the points (span), so a
 * plane stencil takes w (4 + 3 x 8) bytes a point. The 3D one is computed by
 * mpm_shape3_stencil_compute (shape3.h), its row the unit layer along z. */
typedef struct mpm_shape_stencil {
  size_t cap;     /* points it has room for, at width w */
  int w;          /* slots per point */
  int reach;      /* node rows beyond a point's unit row (span) */
  int *count;     /* [cap] nodes per point */
  int *row;       /* [cap] unit row of each point's centre */
  int *node;      /* [cap * w] storage node ids */
  double *S, *dSx, *dSy, *dSz;  /* [cap * w]; dSz only in 3D */
  size_t wcap;    /* room in node, S, dSx, dSy (entries) */
} mpm_shape_stencil;

/* Point p's entry in a stencil once its weights are in its slots: c, the
 * node count (or -1 outside), and the unit row of its centre y. Returns c,
 * or -1 if the centre is outside. */
static inline int mpm_shape_stencil_point(const mpm_mesh *m, mpm_shape_stencil *st, long p,
                                          double y, int c)
{
  double v;
  if (c >= 0 &&
      mpm_mesh_axis_locate(y, m->y0, m->ly, m->idy, m->ny, m->periodic_y, &st->row[p], &v))
    c = -1;
  st->count[p] = c;
  return c;
}

mpm_shape_stencil *mpm_shape_stencil_alloc(size_t cap);
void mpm_shape_stencil_free(mpm_shape_stencil *st);  /* accepts NULL */

/* Room for cap points at width w in dimension dim (2 or 3: dSz too); on
 * failure (MPM_ENOMEM) the old arrays stay valid. */
int mpm_shape_stencil_reserve(mpm_shape_stencil *st, size_t cap, int w, int dim);

/* Stencil of every point (grows st as needed; sets w and reach from the
 * shape's span). A point outside the mesh is MPM_EOUTSIDE with a message
 * naming the point id, its position and time t. */
int mpm_shape_stencil_compute(mpm_shape_stencil *st, const mpm_shape_type *type, const mpm_mesh *m,
                              const mpm_points *pts, double t, mpm_err *err);

#endif
