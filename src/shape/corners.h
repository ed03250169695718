/* corners.h: the CPDI corner rule's pieces (MODEL.md section 3), written once
 * for D = 2 or 3 dimensions: the corner geometry, the corners located along
 * an axis, the span of a stencil, and the two ways of summing the weights
 * (corner.c): the general rule for any extent, and its factorised form for
 * an extent along the axes. Shared by the shapes of the module (ugimp.c, the
 * plane's batched path among them); not part of the library's interface
 * (names mpm_shape_in_*).
 *
 * A point's extent is the parallelepiped of half-vectors r_1 .. r_D, the
 * columns of R (R_dk = r[D k + d]). Its 2^D corners are
 *   x_c = x_p + sum_k s_ck r_k,  s_c in {-1, +1}^D,
 * numbered as the unit corners of the mesh: in 2D (-,-), (+,-), (+,+),
 * (-,+) (x1 .. x4 of MODEL.md); in 3D those four with s_3 = -1, then the
 * same four with s_3 = +1. With N_i(x_c) the element basis at the corners,
 *   S_ip     = 2^-D sum_c N_i(x_c),
 *   gradS_ip = sum_c w_c N_i(x_c),  w_c = 2^-D R^-T s_c,
 * exact for every linear N: sum_c w_c (x_c - x_p)^T
 * = 2^-D R^-T (sum_c s_c s_c^T) R^T = I, as sum_c s_c s_c^T = 2^D I.
 * R^-T = C / det R with C the cofactors of R. In 2D, for corner 1
 * (s = (-1, -1)): w_1 = (1/A)(r1y - r2y, r2x - r1x), A = 4 det R, the rule
 * of MODEL.md; corner 2 gives (1/A)(r1y + r2y, -r1x - r2x), corners 3 and 4
 * the negatives. */
#ifndef MPM_SHAPE_CORNERS_H
#define MPM_SHAPE_CORNERS_H

#include <math.h>

#include "mesh/mesh.h"
#include "shape/shape.h"

/* s_ck as 0 (-1) or 1 (+1): along the first axis the Q4 order
 * 0, 1, 1, 0 (c ^ c/2), along the others bit k of c. */
static inline double mpm_shape_in_corner_sign(int c, int k)
{
  const int bit = k == 0 ? (c ^ c >> 1) & 1 : c >> k & 1;
  return bit ? 1.0 : -1.0;
}

/* Corner geometry of the extent r (D x D, r[D k + d] = component d of
 * r_{k+1}) in D = 2 or 3 dimensions: the offsets off[D c + d] of x_c - x_p
 * and the gradient weights w[D c + d] of w_c, c = 0 .. 2^D - 1. Returns
 * A = 2^D det R (signed; the parallelepiped's volume): when it is 0, w is
 * not finite and the caller takes the delta limit. Each offset and weight
 * is one sum over k in k order, so that D = 2 is the 2D formula term for
 * term (values equal to the last bit; a 0 may differ in sign only, which a
 * sum into 0.0 does not see). */
static inline double mpm_shape_in_corner_rule(int D, const double *r, double *off, double *w)
{
  double C[3][3];  /* cofactors: R^-T = C / det R */
  if (D == 2) {
    C[0][0] = r[3];
    C[0][1] = -r[1];
    C[1][0] = -r[2];
    C[1][1] = r[0];
  } else {
    for (int d = 0; d < 3; d++)
      for (int k = 0; k < 3; k++) {
        const int d1 = (d + 1) % 3, d2 = (d + 2) % 3, k1 = (k + 1) % 3, k2 = (k + 2) % 3;
        C[d][k] = r[3 * k1 + d1] * r[3 * k2 + d2] - r[3 * k2 + d1] * r[3 * k1 + d2];
      }
  }
  double det = r[0] * C[0][0];             /* det R = sum_d R_d1 C_d1 */
  for (int d = 1; d < D; d++)
    det += r[d] * C[d][0];
  const double A = (double)(1 << D) * det;
  const double iA = 1.0 / A;
  for (int c = 0; c < 1 << D; c++)
    for (int d = 0; d < D; d++) {
      double o = mpm_shape_in_corner_sign(c, 0) * r[d];        /* sum_k s_ck R_dk */
      double g = mpm_shape_in_corner_sign(c, 0) * C[d][0];     /* sum_k s_ck C_dk */
      for (int k = 1; k < D; k++) {
        o += mpm_shape_in_corner_sign(c, k) * r[D * k + d];
        g += mpm_shape_in_corner_sign(c, k) * C[d][k];
      }
      off[D * c + d] = o;
      w[D * c + d] = g * iA;                                  /* 2^-D (C s_c)_d / det R */
    }
  return A;
}

/* The nc corner coordinates s[c] along one axis (origin o, length len,
 * unit size 1/ih, n units) located: unit k[c], local u[c]. A non-periodic
 * axis first moves them onto [o, o + len] (clamped onto the face: a loop
 * without branches, which vectorises); a periodic one wraps them. Returns
 * -1 if one is not finite. */
static inline int mpm_shape_in_corners_axis(int nc, const double *s, double o, double len,
                                            double ih, int n, int periodic, int *k, double *u)
{
  if (periodic) {
    for (int c = 0; c < nc; c++)
      if (mpm_mesh_axis_locate(s[c], o, len, ih, n, 1, &k[c], &u[c]))
        return -1;
    return 0;
  }
  const double hi = o + len;
  int bad = 0;
#pragma omp simd reduction(| : bad)
  for (int c = 0; c < nc; c++) {
    double t = s[c] < o ? o : (s[c] > hi ? hi : s[c]);
    bad |= t != t;                           /* NaN: reported, located at o */
    t = t != t ? o : t;
    mpm_mesh_axis_unit(t - o, ih, n, &k[c], &u[c]);
  }
  return bad ? -1 : 0;
}

/* Span of the corners along one axis (unit size 1/ih, n units) for the
 * largest corner reach h = max_p sum_k |r_kd| of the points: the corners
 * span 2 h ih units, so they fall in at most floor(2 h ih) + 2 units and
 * touch one node more (*nodes, capped at cap), and lie at most
 * floor(h ih) + 1 units from the point's own (*reach, capped at n). The
 * small slack covers round-off in the corner positions. */
static inline void mpm_shape_in_span_axis(double h, double ih, int n, int cap, int *nodes,
                                          int *reach)
{
  const double s = 2.0 * h * ih + 1e-6;
  *nodes = s < cap ? (int)s + 3 : cap;
  *reach = 0.5 * s < n ? (int)(0.5 * s) + 1 : n;
}

/* Add the nv values v to the sums col[0..nv-1] of storage node id in the
 * list of *cnt nodes of one point (appended, its sums from 0, the first
 * time): nodes stay in the order they are first met. */
static inline void mpm_shape_in_list_add(int id, int nv, const double *v, int *node,
                                         double *const *col, int *cnt)
{
  int k = 0;
  while (k < *cnt && node[k] != id)
    k++;
  if (k == *cnt) {
    node[k] = id;
    for (int l = 0; l < nv; l++)
      col[l][k] = 0.0;
    (*cnt)++;
  }
  for (int l = 0; l < nv; l++)
    col[l][k] += v[l];
}

/* The general corner rule for a point at x with extent r (r[D k + d],
 * D = m->dim; corners.h above): corners beyond a non-periodic face clamped
 * onto it, periodic axes wrapped, the weights of each corner's element
 * summed per node in corner order, on the block of nodes the corners touch
 * (up to 3 per axis for extents of half a unit or less), listed along the
 * axes from the last (layer, row, column); corners spanning more than a
 * block (wide extents) add node by node. A flat extent (det R = 0) takes the
 * delta weights, the limit of the rule. Returns the node count (at most
 * MPM_STENCIL_W, nodes of weight 0 listed only where a T3 corner of the
 * block lies in no triangle), or -1 when the centre lies outside a
 * non-periodic face, or x, the extent or its corner geometry is not finite. */
int mpm_shape_in_corner_general(const mpm_mesh *m, const double x[3], const double *r,
                                int *node, double *S, double *const dS[3]);

/* The factorised rule puts a corner within MPM_SHAPE_SNAP units of a node
 * on it: a local coordinate that close to 0 or 1 becomes 0 or 1. A point
 * filled one or two to a unit has its corners on nodes, up to round-off
 * (a few ulps of its position in units: below 1e-12 on meshes of up to a
 * few thousand units); without this its weights along an axis would spread
 * over 3 or 4 nodes, the end ones of round-off size, instead of the 2 or 3
 * it weighs. The weights move by at most that much; sum S = 1,
 * sum gradS = 0 and sum (x_i - x_p) gradS = I hold exactly as before. */
#define MPM_SHAPE_SNAP 1e-12
static inline double mpm_shape_in_snap(double l)
{
  return l < MPM_SHAPE_SNAP ? 0.0 : (l > 1.0 - MPM_SHAPE_SNAP ? 1.0 : l);
}

/* The factorised rule of an extent along the axes, r_k = h_k e_k (every
 * uGIMP extent as filled): along axis d the two corner coordinates
 * x_d -+ h_d (clamped and wrapped as in the general rule) give the hat
 * values phi_n of the nodes n they touch, and with A_n = (phi_n(-) +
 * phi_n(+))/2, B_n = (phi_n(+) - phi_n(-))/(2 h_d)
 *   S = prod_d A_d,  dS/dx_d = B_d prod_{e != d} A_e,
 * the general rule's sums regrouped (w_c = R^-T s_c / 2^D = (s_c / h) / 2^D)
 * on the same nodes (those a short periodic axis aliases merged per axis),
 * the corners put on a node they lie within MPM_SHAPE_SNAP of
 * (mpm_shape_in_snap), and the nodes at either end of an axis whose A and B
 * are both 0 left out.
 * For point x in unit c with half-widths h[d] > 0: per axis the storage
 * index of each node along it (ax->idx), its factors A and B, and their
 * number. Returns 0, -1 outside (a corner not finite), or -2 when a corner
 * pair spans more than MPM_SHAPE_AXIS_NODES nodes (the general rule takes
 * it). */
int mpm_shape_in_separable(const mpm_mesh *m, const double x[3], const int c[3],
                           const double h[3], mpm_shape_axes *ax);

/* The factorised weights (mpm_shape_in_separable) of points [lo, hi) into
 * st's axes, count and row (mpm_shape_stencil_point), in batches: first
 * each axis of a batch of points in a loop that vectorises, for the points
 * whose corners along it lie in one unit or two neighbours without a wrap
 * (nearly all: the same values bit for bit), then the others point by
 * point. Returns the first point outside the mesh, or hi; *fits 0 (and the
 * rest undone) when a point's extent does not factorise. */
long mpm_shape_in_separable_range(const mpm_mesh *m, const mpm_points *pts, long lo, long hi,
                                  mpm_shape_stencil *st, int *fits);

/* The weights of the factorised rule as a node list (nodes along the axes
 * from the last, the products of mpm_shape_axes_weight); returns the count. */
int mpm_shape_in_separable_list(const mpm_mesh *m, const mpm_shape_axes *ax, int *node,
                                double *S, double *const dS[3]);

/* The half-widths of an extent along the axes, h[d] = |r_dd|, when it is
 * one (the off-diagonal components zero, the diagonal ones not, and its
 * volume and the general rule's cofactors finite); 0 otherwise. */
static inline int mpm_shape_in_axes_extent(int D, const double *r, double h[3])
{
  for (int k = 0; k < D; k++)
    for (int d = 0; d < D; d++)
      if (d != k && r[D * k + d] != 0.0)
        return 0;
  double v = 1.0;
  for (int d = 0; d < D; d++) {
    h[d] = fabs(r[D * d + d]);
    if (!(h[d] != 0.0))
      return 0;
    v *= h[d];
  }
  if (D != 3)
    h[2] = 0.0;
  const double s = D == 3 ? h[0] * h[1] + h[1] * h[2] + h[2] * h[0] : 0.0;
  return isfinite(v) && isfinite(s);
}

#endif