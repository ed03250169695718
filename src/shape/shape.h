/* shape.h: shape-function variants and the per-point stencil (MODEL.md
 * section 3), on a mesh of either dimension.
 *
 * A variant is a const mpm_shape_type registered in mpm_shape_table (NULL
 * ended) and chosen by name in the input. It produces, for one point, the
 * nodes it touches with weights S_ip and gradients gradS_ip. The stencil holds
 * those for every point, at the width the shape needs for them; the step
 * computes it once and reuses it for point-to-grid and grid-to-point (or,
 * for a shape whose weights are the element basis at the point, evaluates
 * them where it needs them). On boxes, a shape whose points have extents
 * along the axes stores each point's weights factorised by axis (the
 * separable stencil, a few dozen numbers instead of 27 node weights), and
 * the step forms the products where it uses them. */
#ifndef MPM_SHAPE_SHAPE_H
#define MPM_SHAPE_SHAPE_H

#include <stddef.h>

#include "core/error.h"
#include "core/points.h"
#include "mesh/mesh.h"

/* Most nodes one point can touch: 2^D corners x 2^D element nodes before
 * merging, 16 in the plane, 64 on boxes. */
#define MPM_STENCIL_W 64
static inline int mpm_shape_width_cap(int dim)
{
  return dim == 3 ? 64 : 16;
}

/* Most nodes along one axis of the factorised weights: the corners of an
 * extent of half a unit or less (every extent a fill makes) lie in at most
 * three units, round-off at a unit's edge included. */
#define MPM_SHAPE_AXIS_NODES 4

/* The weights of a point factorised by axis (the separable rule, corners.h):
 * along axis d, n[d] nodes with storage indices idx[d][k] along the axis
 * and factors A[d][k], B[d][k]; the node (i, j, k) of the tensor product
 * has S = A_0i (A_1j A_2k) and dS/dx = (B_0i (A_1j A_2k), A_0i (B_1j A_2k),
 * A_0i (A_1j B_2k)) (mpm_shape_axes_weight; in the plane the last factors
 * are dropped). */
typedef struct mpm_shape_axes {
  int n[3];
  int idx[3][MPM_SHAPE_AXIS_NODES];
  double A[3][MPM_SHAPE_AXIS_NODES], B[3][MPM_SHAPE_AXIS_NODES];
} mpm_shape_axes;

struct mpm_shape_stencil;

typedef struct mpm_shape_type {
  const char *name;
  const char *description;
  /* Weights of one point at x with extent half-vectors r (r[D k + d] =
   * component d of r_{k+1}, D the mesh's dimension; either orientation).
   * Writes at most mpm_shape_width_cap distinct nodes, their S and
   * dS[d][k] = dS_k/dx_d (one may have weights 0: a node of the units the
   * point reaches that it does not weigh); returns their count, or -1 when
   * the point lies outside a non-periodic face, or it or its extent is not
   * finite. */
  int (*eval)(const mpm_mesh *m, const double x[3], const double *r, int *node, double *S,
              double *const dS[3]);
  /* Optional, the same for the points [lo, hi) of a plane mesh at once, in
   * a loop the shape can specialise: for each point p the weights in its
   * slots of the stencil st (sized for the points at width st->w), and
   * count[p] and row[p] (mpm_shape_stencil_point); returns the first point
   * outside the mesh, or hi. NULL: eval, point by point. */
  long (*fill)(const mpm_mesh *m, const mpm_points *pts, long lo, long hi,
               struct mpm_shape_stencil *st);
  /* For the points pts on mesh m: *width, the most nodes eval gives one of
   * them (<= mpm_shape_width_cap), and *reach, how many units beyond its own
   * its nodes go along the mesh's last axis (its band axis, mesh.h): a point
   * in unit k there touches nodes k - reach .. k + 1 + reach. */
  void (*span)(const mpm_mesh *m, const mpm_points *pts, int *width, int *reach);
  /* 1 if the weights are the element basis at the point itself (S = N(x_p)):
   * the step then evaluates them from the located point (mpm_mesh_basis_at)
   * where it needs them instead of storing a stencil. */
  int at_point;
  /* 1 if the extent follows the deformation (CPDI1): every step moves the
   * half-vectors with the point's velocity gradient
   * (mpm_shape_extent_convect_dim); 0: the extent stays as filled. */
  int convect;
  /* 1 if a point's weights factorise by axis when its extent lies along
   * the axes (uGIMP): on boxes its stencil is then stored factorised. */
  int separable;
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

/* The extent of point p of store P in the layout of eval (D x D). */
static inline void mpm_shape_point_extent(const mpm_points *P, int D, size_t p, double *r)
{
  for (int k = 0; k < D; k++)
    for (int d = 0; d < D; d++)
      r[D * k + d] = P->ext[k][d][p];
}

/* The weight and gradient of node (i, j, k) of factorised weights ax in D
 * dimensions (indices into the axes' nodes; k = 0 in the plane): the
 * products in the order of mpm_shape_axes. */
static inline double mpm_shape_axes_weight(const mpm_shape_axes *ax, int D, int i, int j, int k,
                                           double g[3])
{
  if (D == 2) {
    g[0] = ax->B[0][i] * ax->A[1][j];
    g[1] = ax->A[0][i] * ax->B[1][j];
    return ax->A[0][i] * ax->A[1][j];
  }
  const double ayz = ax->A[1][j] * ax->A[2][k], byz = ax->B[1][j] * ax->A[2][k];
  const double azb = ax->A[1][j] * ax->B[2][k];
  g[0] = ax->B[0][i] * ayz;
  g[1] = ax->A[0][i] * byz;
  g[2] = ax->A[0][i] * azb;
  return ax->A[0][i] * ayz;
}

extern const mpm_shape_type mpm_shape_delta;  /* S = N(x_p) */
extern const mpm_shape_type mpm_shape_ugimp;  /* CPDI corner rule, fixed extent */
extern const mpm_shape_type mpm_shape_cpdi;   /* CPDI corner rule, convected extent (CPDI1) */
extern const mpm_shape_type *const mpm_shape_table[];

/* Variant by name, NULL if unknown. */
const mpm_shape_type *mpm_shape_lookup(const char *name);

/* The weights of every point of a step, in one of two forms:
 *   a list (sep = 0): point p's nodes are node[p w .. p w + count[p]), their
 *     weights and gradients at the same places of S, dS[0 .. D-1]; w is the
 *     width of the shape for the points (span), so a plane stencil takes
 *     w (4 + 3 x 8) bytes a point;
 *   factorised (sep = 1; on boxes, for a separable shape whose every point
 *     has an extent along the axes): point p's weights are axes[p]
 *     (mpm_shape_axes), count[p] the nodes of their product.
 * row[p] is the unit of the point's centre along the mesh's last axis (its
 * band: mpm_mesh_bands). */
typedef struct mpm_shape_stencil {
  size_t cap;     /* points it has room for, at width w */
  int w;          /* slots per point (the list) */
  int reach;      /* units beyond a point's own along the last axis (span) */
  int dim;        /* of the mesh it was computed on */
  int sep;        /* 1: the factorised form */
  int *count;     /* [cap] nodes per point */
  int *row;       /* [cap] unit of each point's centre along the last axis */
  int *node;      /* [cap * w] storage node ids */
  double *S, *dS[3];  /* [cap * w]; dS[2] on boxes only */
  size_t wcap;    /* room in node, S, dS (entries) */
  mpm_shape_axes *axes;  /* [cap] the factorised weights (sep), else unused */
  size_t acap;    /* room in axes */
} mpm_shape_stencil;

/* Point p's entry in a stencil once its weights are in its slots: c, the
 * node count (or -1 outside), and the unit of its centre coordinate xr
 * along the mesh's last axis. Returns c, or -1 if the centre is outside. */
static inline int mpm_shape_stencil_point(const mpm_mesh *m, mpm_shape_stencil *st, long p,
                                          double xr, int c)
{
  double v;
  if (c >= 0 && mpm_mesh_locate_axis(m, m->dim - 1, xr, &st->row[p], &v))
    c = -1;
  st->count[p] = c;
  return c;
}

mpm_shape_stencil *mpm_shape_stencil_alloc(size_t cap);
void mpm_shape_stencil_free(mpm_shape_stencil *st);  /* accepts NULL */

/* Room for cap points at width w in dimension dim (2 or 3: dS[2] too); on
 * failure (MPM_ENOMEM) the old arrays stay valid. */
int mpm_shape_stencil_reserve(mpm_shape_stencil *st, size_t cap, int w, int dim);

/* Stencil of every point (grows st as needed; sets w and reach from the
 * shape's span, and the form). A point outside the mesh is MPM_EOUTSIDE
 * with a message naming the point id, its position and time t. */
int mpm_shape_stencil_compute(mpm_shape_stencil *st, const mpm_shape_type *type, const mpm_mesh *m,
                              const mpm_points *pts, double t, mpm_err *err);

/* The weights of point p of a computed stencil on mesh m as a node list,
 * whatever the form: writes count nodes (at most mpm_shape_width_cap) and
 * their S, dS[d] into the caller's arrays; returns the count. */
int mpm_shape_stencil_list(const mpm_shape_stencil *st, const mpm_mesh *m, size_t p, int *node,
                           double *S, double *const dS[3]);

#endif
