/* ugimp3.c: the CPDI corner rule on the 3D mesh of boxes (MODEL.md section 3;
 * corners.h with D = 3): uGIMP, the parallelepiped extent (r1, r2, r3) fixed
 * as filled, and CPDI1, the same rule with the extent convected.
 *
 * Corners x_c = x_p + sum_k s_ck r_k, s_c in {-1, +1}^3 (8 corners);
 *   S_ip     = 1/8 sum_c N_i(x_c),
 *   gradS_ip = sum_c w_c N_i(x_c),  w_c = 1/8 R^-T s_c,  R = [r1 r2 r3],
 * on the trilinear basis N; either orientation (det R < 0) is exact.
 * As in 2D (ugimp.c): corners beyond a non-periodic face are clamped onto
 * it, periodic axes wrap, a flat extent (det R = 0) takes the delta weights,
 * and the weights are summed per node, in corner order at every node, on the
 * block of nodes the corners touch (3 x 3 x 3 for extents up to half a
 * unit), listed layer by layer, row by row; corners spanning more than
 * BLOCK - 2 units (wide extents) add node by node to the list instead (at
 * most 8 corners x 8 nodes). Not finite: a point, an extent, or a corner
 * geometry that overflows, reported as outside (-1). An extent along the
 * axes (every uGIMP extent as filled) takes the factorised form of the same
 * rule (ugimp3_box). */
#include "shape/shape3.h"

#include <limits.h>
#include <math.h>
#include <stdint.h>

#include "shape/corners.h"

/* Block side (nodes along each axis): slot a + BLOCK b + BLOCK^2 c. */
enum { BLOCK = 4 };

/* An extent along the axes, r_k = h_k e_k (uGIMP as filled): the corner
 * rule factorises. Along axis d the two corner coordinates x_d -+ |h_d|
 * (clamped and wrapped as in the general rule) give the hat values phi_n
 * of the nodes n they touch, and with A_n = (phi_n(-) + phi_n(+))/2,
 * B_n = (phi_n(+) - phi_n(-))/(2 |h_d|):
 *   S = A_x A_y A_z,  gradS = (B_x A_y A_z, A_x B_y A_z, A_x A_y B_z),
 * the general rule's sums regrouped (w_c = R^-T s_c / 8 = (s_c / h) / 8),
 * on the same nodes in the same order (nodes that a short periodic axis
 * aliases merged per axis, before the products); a few times fewer
 * operations. Returns the count, -1 outside, or -2 when a corner pair spans
 * more than the block (the general rule takes it). */
static int ugimp3_box(const mpm_mesh3 *m, const double x[3], const int uc[3], const double h[3],
                      int *node, double *S, double *dSx, double *dSy, double *dSz)
{
  const double o[3] = {m->x0, m->y0, m->z0}, len[3] = {m->lx, m->ly, m->lz};
  const double ih[3] = {m->idx, m->idy, m->idz};
  const int nu[3] = {m->nx, m->ny, m->nz};
  const int per[3] = {m->periodic_x, m->periodic_y, m->periodic_z};
  double A[3][BLOCK], B[3][BLOCK];
  int sn[3][BLOCK], bs[3];                     /* per axis: stored node index, count */
  for (int d = 0; d < 3; d++) {
    const double s[2] = {x[d] - h[d], x[d] + h[d]};
    int ck[2], dk[2];
    double cl[2];
    if (mpm_shape_in_corners_axis(2, s, o[d], len[d], ih[d], nu[d], per[d], ck, cl))
      return -1;
    for (int c = 0; c < 2; c++)
      dk[c] = mpm_mesh_axis_offset(ck[c] - uc[d], nu[d], per[d]);
    const int lo = dk[0] < dk[1] ? dk[0] : dk[1];
    bs[d] = (dk[0] < dk[1] ? dk[1] : dk[0]) - lo + 2;
    if (bs[d] > BLOCK)
      return -2;
    for (int n = 0; n < BLOCK; n++)
      A[d][n] = B[d][n] = 0.0;
    const double ib = 0.5 / h[d];
    for (int c = 0; c < 2; c++) {              /* corner -h (c = 0), +h (c = 1) */
      const int at = dk[c] - lo;
      const double phi[2] = {1.0 - cl[c], cl[c]}, sg = c ? ib : -ib;
      for (int a = 0; a < 2; a++) {
        A[d][at + a] += 0.5 * phi[a];
        B[d][at + a] += sg * phi[a];
      }
    }
    int cnt = 0;                               /* stored nodes; on a periodic axis of */
    for (int n = 0; n < bs[d]; n++) {          /* few units one can come twice: merged */
      const int id = mpm_mesh_axis_node(uc[d] + lo + n, nu[d], per[d]);
      int q = 0;
      while (q < cnt && sn[d][q] != id)
        q++;
      if (q == cnt) {
        sn[d][cnt] = id;
        A[d][cnt] = A[d][n];
        B[d][cnt] = B[d][n];
        cnt++;
      } else {
        A[d][q] += A[d][n];
        B[d][q] += B[d][n];
      }
    }
    bs[d] = cnt;
  }
  int cnt = 0;
  for (int k = 0; k < bs[2]; k++)
    for (int j = 0; j < bs[1]; j++) {
      const double ayz = A[1][j] * A[2][k], byz = B[1][j] * A[2][k], azb = A[1][j] * B[2][k];
      const int row = (sn[2][k] * m->sny + sn[1][j]) * m->snx;
      for (int i = 0; i < bs[0]; i++) {
        node[cnt] = row + sn[0][i];
        S[cnt] = A[0][i] * ayz;
        dSx[cnt] = B[0][i] * ayz;
        dSy[cnt] = A[0][i] * byz;
        dSz[cnt] = A[0][i] * azb;
        cnt++;
      }
    }
  return cnt;
}

static int ugimp3_eval(const mpm_mesh3 *m, const double x[3], const double r[9], int *node,
                       double *S, double *dSx, double *dSy, double *dSz)
{
  int uc[3];
  double lc[3];
  if (mpm_mesh3_locate(m, x, uc, lc))
    return -1;                               /* the centre decides */
  if (r[1] == 0.0 && r[2] == 0.0 && r[3] == 0.0 && r[5] == 0.0 && r[6] == 0.0 && r[7] == 0.0 &&
      r[0] != 0.0 && r[4] != 0.0 && r[8] != 0.0) {        /* along the axes: a box */
    const double h[3] = {fabs(r[0]), fabs(r[4]), fabs(r[8])};
    /* the general rule's volume and cofactors finite, or it reports -1 */
    if (isfinite(h[0] * h[1] * h[2]) && isfinite(h[0] * h[1] + h[1] * h[2] + h[0] * h[2])) {
      const int c = ugimp3_box(m, x, uc, h, node, S, dSx, dSy, dSz);
      if (c != -2)
        return c;
    }
  }
  double co[24], wg[24];                     /* offsets x_c - x_p, weights w_c */
  const double A = mpm_shape_in_corner_rule(3, r, co, wg);
  if (!isfinite(A))
    return -1;                               /* extent not finite (or overflowing) */
  if (A == 0.0)                              /* flat: the delta limit */
    return mpm_mesh3_basis_at(m, uc, lc, node, S, dSx, dSy, dSz);
  int fin = 1;
  for (int q = 0; q < 24; q++)
    fin &= isfinite(co[q]) && isfinite(wg[q]);
  if (!fin)
    return -1;
  /* per axis d: the corners located, unit ck (storage) and local cl, their
   * offsets dk from the centre's unit, the block's first offset lo and its
   * side bs in nodes */
  const double o[3] = {m->x0, m->y0, m->z0}, len[3] = {m->lx, m->ly, m->lz};
  const double ih[3] = {m->idx, m->idy, m->idz};
  const int nu[3] = {m->nx, m->ny, m->nz};
  const int per[3] = {m->periodic_x, m->periodic_y, m->periodic_z};
  int ck[3][8], dk[3][8], lo[3], bs[3], wide = 0;
  double cl[3][8];
  for (int d = 0; d < 3; d++) {
    double s[8];
    for (int c = 0; c < 8; c++)
      s[c] = x[d] + co[3 * c + d];
    if (mpm_shape_in_corners_axis(8, s, o[d], len[d], ih[d], nu[d], per[d], ck[d], cl[d]))
      return -1;
    int a0 = INT_MAX, a1 = INT_MIN;
    for (int c = 0; c < 8; c++) {
      dk[d][c] = mpm_mesh_axis_offset(ck[d][c] - uc[d], nu[d], per[d]);
      a0 = dk[d][c] < a0 ? dk[d][c] : a0;
      a1 = dk[d][c] > a1 ? dk[d][c] : a1;
    }
    lo[d] = a0;
    bs[d] = a1 - a0 + 2;
    wide |= bs[d] > BLOCK;
  }
  double *const col[4] = {S, dSx, dSy, dSz};
  int cnt = 0;
  if (wide) {                                /* node by node, in corner order */
    for (int c = 0; c < 8; c++) {
      double N[8];
      int id[8];
      mpm_mesh3_shape_q8(cl[0][c], cl[1][c], cl[2][c], N);
      mpm_mesh3_unit_corners(m, ck[0][c], ck[1][c], ck[2][c], id);
      for (int a = 0; a < 8; a++) {
        const double v[4] = {0.125 * N[a], wg[3 * c] * N[a], wg[3 * c + 1] * N[a],
                             wg[3 * c + 2] * N[a]};
        mpm_shape_in_list_add(id[a], 4, v, node, col, &cnt);
      }
    }
    return cnt;
  }
  /* S += N/8, gradS += w_c N on the nodes of each corner's unit, as records
   * (S, gx, gy, gz): one vector operation per node of a corner */
  double blk[BLOCK * BLOCK * BLOCK][4];
  for (int k = 0; k < bs[2]; k++)
    for (int j = 0; j < bs[1]; j++)
      for (int i = 0; i < bs[0]; i++)
        for (int l = 0; l < 4; l++)
          blk[i + BLOCK * (j + BLOCK * k)][l] = 0.0;
  /* slots of the unit corners 0..7 (hexahedron order) from corner 0's */
  const int slot[8] = {0, 1, BLOCK + 1, BLOCK, BLOCK * BLOCK, BLOCK * BLOCK + 1,
                       BLOCK * BLOCK + BLOCK + 1, BLOCK * BLOCK + BLOCK};
  uint64_t pat = 0;                          /* the slots as bits */
  for (int a = 0; a < 8; a++)
    pat |= (uint64_t)1 << slot[a];
  uint64_t used = 0;
  for (int c = 0; c < 8; c++) {
    double N[8];
    mpm_mesh3_shape_q8(cl[0][c], cl[1][c], cl[2][c], N);
    const double G[4] = {0.125, wg[3 * c], wg[3 * c + 1], wg[3 * c + 2]};
    const int at = dk[0][c] - lo[0] + BLOCK * (dk[1][c] - lo[1] + BLOCK * (dk[2][c] - lo[2]));
    used |= pat << at;
    for (int a = 0; a < 8; a++) {
      double *b = blk[at + slot[a]];
#pragma omp simd
      for (int l = 0; l < 4; l++)
        b[l] += G[l] * N[a];
    }
  }
  /* the used nodes layer by layer, row by row; on a periodic axis of few
   * units two of them can be one stored node: merged */
  int merge = 0;
  for (int d = 0; d < 3; d++)
    merge |= per[d] && nu[d] < bs[d];
  for (int k = 0; k < bs[2]; k++) {
    const int ks = mpm_mesh_axis_node(uc[2] + lo[2] + k, m->nz, m->periodic_z);
    for (int j = 0; j < bs[1]; j++) {
      const int js = mpm_mesh_axis_node(uc[1] + lo[1] + j, m->ny, m->periodic_y);
      for (int i = 0; i < bs[0]; i++) {
        const int q = i + BLOCK * (j + BLOCK * k);
        if (!(used >> q & 1u))
          continue;
        const int id = (ks * m->sny + js) * m->snx +
                       mpm_mesh_axis_node(uc[0] + lo[0] + i, m->nx, m->periodic_x);
        if (merge) {
          mpm_shape_in_list_add(id, 4, blk[q], node, col, &cnt);
          continue;
        }
        node[cnt] = id;
        S[cnt] = blk[q][0];
        dSx[cnt] = blk[q][1];
        dSy[cnt] = blk[q][2];
        dSz[cnt] = blk[q][3];
        cnt++;
      }
    }
  }
  return cnt;
}

/* The corners of a point lie within h_d = sum_k |r_kd| of it along axis d;
 * the nodes they touch and the units they reach follow per axis
 * (mpm_shape_in_span_axis, as in 2D). */
static void ugimp3_span(const mpm_mesh3 *m, size_t n, const double *r, int *width, int *reach)
{
  double h[3] = {0.0, 0.0, 0.0};
  for (size_t p = 0; p < n; p++)
    for (int d = 0; d < 3; d++) {
      const double a = fabs(r[9 * p + d]) + fabs(r[9 * p + 3 + d]) + fabs(r[9 * p + 6 + d]);
      h[d] = a > h[d] ? a : h[d];
    }
  const double ih[3] = {m->idx, m->idy, m->idz};
  const int nu[3] = {m->nx, m->ny, m->nz};
  int w = 1, re = 0;
  for (int d = 0; d < 3; d++) {
    int nd, rd;
    mpm_shape_in_span_axis(h[d], ih[d], nu[d], MPM_STENCIL3_W, &nd, &rd);
    w *= nd;                                                  /* nodes along d; <= 64^3 */
    re = rd > re ? rd : re;
  }
  *width = w < MPM_STENCIL3_W ? w : MPM_STENCIL3_W;
  *reach = re;
}

const mpm_shape3_type mpm_shape3_ugimp = {
  .name = "ugimp",
  .description = "uGIMP, CPDI corner rule with a fixed parallelepiped extent (r1, r2, r3)",
  .eval = ugimp3_eval,
  .span = ugimp3_span,
  .at_point = 0,
  .convect = 0,
};

const mpm_shape3_type mpm_shape3_cpdi = {
  .name = "cpdi",
  .description = "CPDI1, the corner rule with the extent (r1, r2, r3) convected by the "
                 "deformation",
  .eval = ugimp3_eval,
  .span = ugimp3_span,
  .at_point = 0,
  .convect = 1,
};
