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
 * touched nodes listed in row order.
 *
 * An extent along the mesh axes (r1 = (r1x, 0), r2 = (0, r2y): every uGIMP
 * point as filled) whose corners lie inside the mesh, neither clamped nor
 * wrapped, is located by its two corner columns and two corner rows, with
 * the weights of the rule written out (eval_axes): the same values, bit for
 * bit, as the general path (eval_general), in about half the instructions. */
#include "shape/shape.h"

#include <math.h>
#include <stdlib.h>

#include "shape/corners.h"

/* The logical nodes a point's corners touch form a block of node columns
 * and rows next to the unit of its centre: at most 3 x 3 for extents up to
 * half a unit. The weights are summed on a BLOCK x BLOCK array (slot
 * a + BLOCK b); corners spanning more than BLOCK - 2 units (wide extents)
 * add node by node to the list instead. */
enum { BLOCK = 4 };

/* The block's sums as records (S, gx, gy, 0) of four lanes, slot a + BLOCK b
 * for block node column a, row b. */
typedef double block[BLOCK * BLOCK][4];

/* Zero the slots of a block of bw x bh nodes. */
static inline void block_zero(block blk, int bw, int bh)
{
  for (int b = 0; b < bh; b++)
    for (int a = 0; a < bw; a++)
      for (int l = 0; l < 4; l++)
        blk[a + BLOCK * b][l] = 0.0;
}

/* S += N/4, gradS += (wx, wy) N on the element of one corner, its unit's
 * first corner at slot `at`, its element mask `mask` (N of the four unit
 * corners): one vector operation per unit corner (a T3 element's fourth
 * corner has N = 0: it adds nothing and is not marked used). Returns the
 * slots it uses, as bits. */
static inline unsigned block_add(block blk, int at, unsigned mask, const double N[4], double wx,
                                 double wy)
{
  const int off[4] = {0, 1, BLOCK + 1, BLOCK};       /* slots of unit corners 0..3 */
  const double G[4] = {0.25, wx, wy, 0.0};
  for (int a = 0; a < 4; a++) {
    double *b = blk[at + off[a]];
#pragma omp simd
    for (int l = 0; l < 4; l++)
      b[l] += G[l] * N[a];
  }
  return ((mask & 3u) | (mask & 4u) << 3 | (mask & 8u) << 1) << at;
}

/* block_add for a corner at local (u, v) of the unit at block column a, row
 * b, of topology ti (cut along "/" if slash), gradient weights (wx, wy). */
static inline unsigned corner_add(block blk, int ti, int slash, double u, double v, int a, int b,
                                  double wx, double wy)
{
  double N[4];
  const unsigned mask = mpm_mesh_shape_unit(ti, slash, u, v, N);
  return block_add(blk, a + BLOCK * b, mask, N, wx, wy);
}

/* The used slots' nodes in row order (the set bits of `used`, s = a + BLOCK b,
 * from the lowest), the block's first logical node (ib, jb): returns their
 * count. When neither axis wraps within the block, node a, b is stored at
 * (jb + b) snx + ib + a; otherwise (ib or jb may be negative on a periodic
 * axis) each is aliased through
 * mpm_mesh_axis_node, and on a periodic axis of fewer units than the block
 * two of them can be one stored node: merged. */
static inline int block_list(const mpm_mesh *m, const block blk, unsigned used, int ib, int jb,
                             int bw, int bh, int *node, double *S, double *dSx, double *dSy)
{
  int cnt = 0;
  if (!(m->periodic_x && (ib < 0 || ib + bw > m->nx)) &&
      !(m->periodic_y && (jb < 0 || jb + bh > m->ny))) {
    const int n0 = jb * m->snx + ib, snx = m->snx;
    for (unsigned u = used; u; u &= u - 1) {
      const int s = mpm_shape_in_lowest_bit(u);
      node[cnt] = n0 + (s & (BLOCK - 1)) + (s / BLOCK) * snx;
      S[cnt] = blk[s][0];
      dSx[cnt] = blk[s][1];
      dSy[cnt] = blk[s][2];
      cnt++;
    }
    return cnt;
  }
  double *const col[3] = {S, dSx, dSy};
  const int merge = (m->periodic_x && m->nx < bw) || (m->periodic_y && m->ny < bh);
  int is[BLOCK], js[BLOCK];                  /* storage column, row offset of the block */
  for (int a = 0; a < bw; a++)
    is[a] = mpm_mesh_axis_node(ib + a, m->nx, m->periodic_x);
  for (int b = 0; b < bh; b++)
    js[b] = mpm_mesh_axis_node(jb + b, m->ny, m->periodic_y) * m->snx;
  for (unsigned u = used; u; u &= u - 1) {
    const int s = mpm_shape_in_lowest_bit(u);
    const int id = js[s / BLOCK] + is[s % BLOCK];
    if (merge) {
      mpm_shape_in_list_add(id, 3, blk[s], node, col, &cnt);
      continue;
    }
    node[cnt] = id;
    S[cnt] = blk[s][0];
    dSx[cnt] = blk[s][1];
    dSy[cnt] = blk[s][2];
    cnt++;
  }
  return cnt;
}

/* Any extent: the corner rule, corners clamped onto non-periodic edges or
 * wrapped round periodic ones. */
static int eval_general(const mpm_mesh *m, double x, double y, const double r[4], int *node,
                        double *S, double *dSx, double *dSy)
{
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
  if (bw > BLOCK || bh > BLOCK) {            /* wide: node by node into the list */
    double *const col[3] = {S, dSx, dSy};
    int cnt = 0;
    for (int c = 0; c < 4; c++) {
      double N[4];
      int id[4];
      const unsigned mask = mpm_mesh_shape_corners(m, ci[c], cu[c], cv[c], N);
      mpm_mesh_unit_corners(m, ci[c], cj[c], id);
      for (int a = 0; a < 4; a++)
        if (mask >> a & 1u) {
          const double v[3] = {0.25 * N[a], wg[2 * c] * N[a], wg[2 * c + 1] * N[a]};
          mpm_shape_in_list_add(id[a], 3, v, node, col, &cnt);
        }
    }
    return cnt;
  }
  block blk;
  block_zero(blk, bw, bh);
  unsigned used = 0;
  for (int c = 0; c < 4; c++) {
    double N[4];
    const unsigned mask = mpm_mesh_shape_corners(m, ci[c], cu[c], cv[c], N);
    used |= block_add(blk, di[c] - i0 + BLOCK * (dj[c] - j0), mask, N, wg[2 * c],
                      wg[2 * c + 1]);
  }
  return block_list(m, blk, used, iu + i0, ju + j0, bw, bh, node, S, dSx, dSy);
}

/* An extent along the axes, r = (r1x, 0, 0, r2y), its corners inside the
 * mesh: corner columns x -+ r1x, rows y -+ r2y (corner c on column side
 * (c ^ c >> 1) & 1 and row side c >> 1, corners.h), each located once,
 * without clamping or wrapping (the centre lies between them: it needs no
 * locating). The rule's sums with r1y = r2x = 0 reduce exactly to
 * A = 4 r1x r2y and w_c = (-+ r2y / A, -+ r1x / A) (its products with 0
 * add nothing but a sign of zero), so the weights are the general path's
 * bit for bit. Returns the node count, or -2 when the case does not apply
 * (another extent, a corner outside, a block wider than BLOCK - 1 units, a
 * periodic axis of few units). */
static int eval_axes(const mpm_mesh *m, double x, double y, const double r[4], int *node,
                     double *S, double *dSx, double *dSy)
{
  if (r[1] != 0.0 || r[2] != 0.0)
    return -2;
  const double A = 4.0 * (r[0] * r[3]);
  /* lanes: the corner columns x - r1x, x + r1x, the corner rows y - r2y, y + r2y */
  const double c[4] = {x - r[0], x + r[0], y - r[3], y + r[3]};
  const double o[4] = {m->x0, m->x0, m->y0, m->y0}, len[4] = {m->lx, m->lx, m->ly, m->ly};
  const double ih[4] = {m->idx, m->idx, m->idy, m->idy};
  const int n[4] = {m->nx, m->nx, m->ny, m->ny};
  int k[4], out = !(A != 0.0 && isfinite(A));
  double u[4];
#pragma omp simd reduction(| : out)
  for (int l = 0; l < 4; l++) {              /* unclamped, unwrapped (corners.h) */
    const double s = c[l] - o[l];
    out |= !(s >= 0.0) | !(s < len[l]) | !(c[l] <= o[l] + len[l]);
    mpm_mesh_axis_unit(s, ih[l], n[l], &k[l], &u[l]);
  }
  const int i0 = k[0] < k[1] ? k[0] : k[1], j0 = k[2] < k[3] ? k[2] : k[3];
  const int bw = abs(k[1] - k[0]) + 2, bh = abs(k[3] - k[2]) + 2;
  if (out || bw > 3 || bh > 3 || (m->periodic_x && m->nx < 3) || (m->periodic_y && m->ny < 3))
    return -2;                               /* wide; the general rule's nearest image */
  const double iA = 1.0 / A, gx = r[3] * iA, gy = r[0] * iA;
  const int t3 = m->topology == MPM_TOPO_T3;
  const int slash[2] = {t3 && mpm_mesh_column_is_slash(m, k[0]),
                        t3 && mpm_mesh_column_is_slash(m, k[1])};
  block blk;
  for (int q = 0; q < 3 * BLOCK; q++)        /* rows 0 .. 2 */
    for (int l = 0; l < 4; l++)
      blk[q][l] = 0.0;
  /* corner q on column side (q ^ q >> 1) & 1 and row side q >> 1, in corner order */
  const int ti = m->topology, a0 = k[0] - i0, a1 = k[1] - i0, b0 = k[2] - j0, b1 = k[3] - j0;
  unsigned used = corner_add(blk, ti, slash[0], u[0], u[2], a0, b0, -gx, -gy);
  used |= corner_add(blk, ti, slash[1], u[1], u[2], a1, b0, gx, -gy);
  used |= corner_add(blk, ti, slash[1], u[1], u[3], a1, b1, gx, gy);
  used |= corner_add(blk, ti, slash[0], u[0], u[3], a0, b1, -gx, gy);
  return block_list(m, blk, used, i0, j0, bw, bh, node, S, dSx, dSy);
}

/* One point: along the axes if the case applies, otherwise the general rule;
 * m a copy of the mesh (no store through node, S, dSx, dSy can change it). */
static inline int eval_point(const mpm_mesh *m, double x, double y, const double r[4], int *node,
                             double *S, double *dSx, double *dSy)
{
  const int n = eval_axes(m, x, y, r, node, S, dSx, dSy);
  return n != -2 ? n : eval_general(m, x, y, r, node, S, dSx, dSy);
}

static int ugimp_eval(const mpm_mesh *mesh, double x, double y, const double r[4],
                      int *node, double *S, double *dSx, double *dSy)
{
  const mpm_mesh mc = *mesh;
  return eval_point(&mc, x, y, r, node, S, dSx, dSy);
}

/* The points [lo, hi) with eval_point inlined in the loop. */
static long ugimp_fill(const mpm_mesh *mesh, const mpm_points *pts, long lo, long hi,
                       mpm_shape_stencil *st)
{
  const mpm_mesh mc = *mesh;
  return mpm_shape_eval_range(eval_point, &mc, pts, lo, hi, st);
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
  .fill = ugimp_fill,
  .span = ugimp_span,
  .at_point = 0,
  .convect = 0,
};

const mpm_shape_type mpm_shape_cpdi = {
  .name = "cpdi",
  .description = "CPDI1, the corner rule with the extent (r1, r2) convected by the deformation",
  .eval = ugimp_eval,
  .fill = ugimp_fill,
  .span = ugimp_span,
  .at_point = 0,
  .convect = 1,
};
