/* ugimp.c: the CPDI corner rule (MODEL.md section 3, [DK-silo] App. B):
 * uGIMP, with the extent fixed as filled, and CPDI1, the same rule with the
 * extent convected by the deformation (the step moves r1, r2 with the
 * point's velocity gradient: mpm_shape_extent_convect).
 *
 * Corners x1 = xp - r1 - r2, x2 = xp + r1 - r2, x3 = xp + r1 + r2,
 * x4 = xp - r1 + r2;
 *   S_ip     = 1/4 sum_c N_i(x_c),
 *   gradS_ip = (1/A_p) { [N_i(x1) - N_i(x3)] (r1y - r2y, r2x - r1x)
 *                      + [N_i(x2) - N_i(x4)] (r1y + r2y, -r1x - r2x) },
 *   A_p = 4 (r1x r2y - r1y r2x), signed.
 * The corner offsets and weights come from the rule written once for 2D and
 * 3D (corners.h, D = 2: the same floating-point sums as the formula above).
 * Corners beyond a non-periodic edge are clamped onto it (then the first-order
 * invariants hold only approximately there); periodic directions wrap through
 * the mesh basis. An extent of zero area falls back to the delta weights, the
 * limit of the rule as the extent shrinks.
 * The corners' weights are summed on the block of nodes they touch (3 x 3
 * for extents up to half a unit), in corner order at every node, and the
 * touched nodes listed in row order. */
#include "shape/shape.h"

#include <math.h>

#include "shape/corners.h"

/* The logical nodes a point's corners touch form a block of node columns
 * and rows next to the unit of its centre: at most 3 x 3 for extents up to
 * half a unit. The weights are summed on a BLOCK x BLOCK array (slot
 * a + BLOCK b); corners spanning more than BLOCK - 2 units (wide extents)
 * add node by node to the list instead. */
enum { BLOCK = 4 };

static int ugimp_eval(const mpm_mesh *mesh, double x, double y, const double r[4],
                      int *node, double *S, double *dSx, double *dSy)
{
  const mpm_mesh mc = *mesh, *m = &mc;       /* a copy: no store below can change it */
  int iu, ju;
  double uu, vu;
  if (mpm_mesh_locate(m, x, y, &iu, &ju, &uu, &vu))
    return -1;                               /* the centre decides */
  /* corner offsets x_c - x_p, c = 1..4, and gradient weights w_c (corners.h):
   * +a, +b, -a, -b with a = (r1y - r2y, r2x - r1x)/A,
   * b = (r1y + r2y, -r1x - r2x)/A, A = A_p = 4 (r1x r2y - r1y r2x), signed */
  double co[8], wg[8];
  const double A = mpm_shape_in_corner_rule(2, r, co, wg);
  if (A == 0.0)
    return mpm_mesh_basis_at(m, iu, ju, uu, vu, node, S, dSx, dSy);
  if (!isfinite(A))
    return -1;                               /* a non-finite extent */
  /* the corners located: unit (ci, cj) (storage), offset (di, dj) from the
   * centre's unit, local (cu, cv) */
  int ci[4], cj[4], di[4], dj[4];
  double cx[4], cy[4], cu[4], cv[4];
  for (int c = 0; c < 4; c++) {
    cx[c] = x + co[2 * c];
    cy[c] = y + co[2 * c + 1];
  }
  if (mpm_shape_in_corners_axis(4, cx, m->x0, m->lx, m->idx, m->nx, m->periodic_x, ci, cu) ||
      mpm_shape_in_corners_axis(4, cy, m->y0, m->ly, m->idy, m->ny, m->periodic_y, cj, cv))
    return -1;                               /* non-finite extent */
  for (int c = 0; c < 4; c++) {
    di[c] = mpm_mesh_axis_offset(ci[c] - iu, m->nx, m->periodic_x);
    dj[c] = mpm_mesh_axis_offset(cj[c] - ju, m->ny, m->periodic_y);
  }
  int i0 = di[0], i1 = di[0], j0 = dj[0], j1 = dj[0];
  for (int c = 1; c < 4; c++) {
    i0 = di[c] < i0 ? di[c] : i0;
    i1 = di[c] > i1 ? di[c] : i1;
    j0 = dj[c] < j0 ? dj[c] : j0;
    j1 = dj[c] > j1 ? dj[c] : j1;
  }
  const int bw = i1 - i0 + 2, bh = j1 - j0 + 2;   /* node columns and rows touched */
  const int wide = bw > BLOCK || bh > BLOCK;
  /* S += N/4, gradS += w_c N on the nodes of each corner's element, as
   * records (S, gx, gy, 0) of four lanes: one vector operation per node of
   * a corner (a T3 element's fourth unit corner has N = 0: it adds nothing
   * and is not marked used) */
  double blk[BLOCK * BLOCK][4];
  for (int b = 0; b < bh && !wide; b++)
    for (int a = 0; a < bw; a++)
      for (int l = 0; l < 4; l++)
        blk[a + BLOCK * b][l] = 0.0;
  const int off[4] = {0, 1, BLOCK + 1, BLOCK};       /* slots of unit corners 0..3 */
  unsigned used = 0;
  int cnt = 0;
  double *const col[3] = {S, dSx, dSy};
  for (int c = 0; c < 4; c++) {
    double N[4];
    const unsigned mask = mpm_mesh_shape_corners(m, ci[c], cu[c], cv[c], N);
    const double G[4] = {0.25, wg[2 * c], wg[2 * c + 1], 0.0};
    if (wide) {
      int id[4];
      mpm_mesh_unit_corners(m, ci[c], cj[c], id);
      for (int a = 0; a < 4; a++)
        if (mask >> a & 1u) {
          const double v[3] = {G[0] * N[a], G[1] * N[a], G[2] * N[a]};
          mpm_shape_in_list_add(id[a], 3, v, node, col, &cnt);
        }
      continue;
    }
    const int at = di[c] - i0 + BLOCK * (dj[c] - j0);  /* slot of unit corner 0 */
    used |= ((mask & 3u) | (mask & 4u) << 3 | (mask & 8u) << 1) << at;
    for (int a = 0; a < 4; a++) {
      double *b = blk[at + off[a]];
#pragma omp simd
      for (int l = 0; l < 4; l++)
        b[l] += G[l] * N[a];
    }
  }
  if (wide)
    return cnt;
  /* the used nodes in row order (the set bits of `used`, k = a + BLOCK b,
   * from the lowest); on a periodic axis of few units two of them can be
   * one stored node: merged */
  const int merge = (m->periodic_x && m->nx < bw) || (m->periodic_y && m->ny < bh);
  int is[BLOCK], js[BLOCK];                  /* storage column, row offset of the block */
  for (int a = 0; a < bw; a++)
    is[a] = mpm_mesh_axis_node(iu + i0 + a, m->nx, m->periodic_x);
  for (int b = 0; b < bh; b++)
    js[b] = mpm_mesh_axis_node(ju + j0 + b, m->ny, m->periodic_y) * m->snx;
  for (unsigned u = used; u; u &= u - 1) {
    const int k = mpm_shape_in_lowest_bit(u);
    const int id = js[k / BLOCK] + is[k % BLOCK];
    if (merge) {
      mpm_shape_in_list_add(id, 3, blk[k], node, col, &cnt);
      continue;
    }
    node[cnt] = id;
    S[cnt] = blk[k][0];
    dSx[cnt] = blk[k][1];
    dSy[cnt] = blk[k][2];
    cnt++;
  }
  return cnt;
}

/* The corners of a point lie within hx = |r1x| + |r2x|, hy = |r1y| + |r2y|
 * of it; the node columns and rows they touch and the rows they reach
 * follow per axis (mpm_shape_in_span_axis). */
static void ugimp_span(const mpm_mesh *m, const mpm_points *pts, int *width, int *reach)
{
  double hx = 0.0, hy = 0.0;
#pragma omp simd reduction(max : hx, hy)
  for (size_t p = 0; p < pts->n; p++) {
    const double ax = fabs(pts->r1x[p]) + fabs(pts->r2x[p]);
    const double ay = fabs(pts->r1y[p]) + fabs(pts->r2y[p]);
    hx = ax > hx ? ax : hx;
    hy = ay > hy ? ay : hy;
  }
  int cols, rows, rx;                        /* node columns and rows, reaches */
  mpm_shape_in_span_axis(hx, m->idx, m->nx, MPM_STENCIL_W, &cols, &rx);
  mpm_shape_in_span_axis(hy, m->idy, m->ny, MPM_STENCIL_W, &rows, reach);
  *width = cols * rows < MPM_STENCIL_W ? cols * rows : MPM_STENCIL_W;
}

const mpm_shape_type mpm_shape_ugimp = {
  .name = "ugimp",
  .description = "uGIMP, CPDI corner rule with a fixed parallelogram extent (r1, r2)",
  .eval = ugimp_eval,
  .span = ugimp_span,
  .at_point = 0,
  .convect = 0,
};

const mpm_shape_type mpm_shape_cpdi = {
  .name = "cpdi",
  .description = "CPDI1, the corner rule with the extent (r1, r2) convected by the deformation",
  .eval = ugimp_eval,
  .span = ugimp_span,
  .at_point = 0,
  .convect = 1,
};
