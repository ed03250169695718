/* corner.c: the CPDI corner rule (MODEL.md section 3, [DK-silo] App. B)
 * summed over a mesh of either dimension (corners.h):
 *   S_ip     = 2^-D sum_c N_i(x_c),
 *   gradS_ip = sum_c w_c N_i(x_c),  w_c = 2^-D R^-T s_c,
 * in the general form for any extent, and factorised by axis for an extent
 * along the axes. In the plane the general form is [DK-silo]'s
 *   gradS_ip = (1/A_p) { [N_i(x1) - N_i(x3)] (r1y - r2y, r2x - r1x)
 *                      + [N_i(x2) - N_i(x4)] (r1y + r2y, -r1x - r2x) },
 * A_p = 4 (r1x r2y - r1y r2x), term for term. Corners beyond a non-periodic
 * face are clamped onto it (then the first-order invariants hold only
 * approximately there); periodic axes wrap through the mesh basis. */
#include <limits.h>
#include <math.h>
#include <stdint.h>

#include "shape/corners.h"

/* Block side (nodes along each axis): slot a + BLOCK b (+ BLOCK^2 c). */
enum { BLOCK = 4 };

/* Points a batch of the factorised rule locates at once. */
enum { BATCH = 64 };

/* The general rule in D dimensions (D = m->dim, a constant where it is
 * inlined). */
static inline __attribute__((always_inline)) int
general(const mpm_mesh *m, int D, const double x[3], const double *r, int *node, double *S,
        double *const dS[3])
{
  int uc[3];
  double lc[3];
  if (mpm_mesh_locate(m, x, uc, lc))
    return -1;                               /* the centre decides */
  double co[24], wg[24];                     /* offsets x_c - x_p, weights w_c */
  const double A = mpm_shape_in_corner_rule(D, r, co, wg);
  if (A == 0.0)                              /* flat: the delta limit */
    return mpm_mesh_basis_at(m, uc, lc, node, S, dS);
  if (!isfinite(A))
    return -1;                               /* extent not finite (or overflowing) */
  const int nc = 1 << D;
  int fin = 1;
  for (int q = 0; q < D * nc; q++)
    fin &= isfinite(co[q]) && isfinite(wg[q]);
  if (!fin)
    return -1;
  /* per axis d: the corners located, unit ck (storage) and local cl, their
   * offsets dk from the centre's unit, the block's first offset lo and its
   * side bs in nodes */
  int ck[3][8], dk[3][8], lo[3] = {0, 0, 0}, bs[3] = {1, 1, 1}, wide = 0;
  double cl[3][8];
  for (int d = 0; d < D; d++) {
    double s[8];
    for (int c = 0; c < nc; c++)
      s[c] = x[d] + co[D * c + d];
    if (mpm_shape_in_corners_axis(nc, s, m->o[d], m->len[d], m->ih[d], m->n[d], m->periodic[d],
                                  ck[d], cl[d]))
      return -1;
    int a0 = INT_MAX, a1 = INT_MIN;
    for (int c = 0; c < nc; c++) {
      dk[d][c] = mpm_mesh_axis_offset(ck[d][c] - uc[d], m->n[d], m->periodic[d]);
      a0 = dk[d][c] < a0 ? dk[d][c] : a0;
      a1 = dk[d][c] > a1 ? dk[d][c] : a1;
    }
    lo[d] = a0;
    bs[d] = a1 - a0 + 2;
    wide |= bs[d] > BLOCK;
  }
  for (int c = 0; c < nc; c++)
    ck[2][c] = D == 3 ? ck[2][c] : 0;
  double *const col[4] = {S, dS[0], dS[1], dS[2]};
  int cnt = 0;
  /* S += N / 2^D, gradS += w_c N on the nodes of each corner's element, as
   * records (S, g_x, g_y[, g_z]): one vector operation per node of a corner
   * (a T3 element's fourth unit corner has N = 0: it adds nothing and is not
   * marked used) */
  const double share = D == 3 ? 0.125 : 0.25;
  if (wide) {                                /* node by node, in corner order */
    for (int c = 0; c < nc; c++) {
      double N[8];
      int id[8];
      const int cu[3] = {ck[0][c], ck[1][c], ck[2][c]};
      const double cv[3] = {cl[0][c], cl[1][c], D == 3 ? cl[2][c] : 0.0};
      const unsigned mask = mpm_mesh_shape_corners(m, cu, cv, N);
      mpm_mesh_unit_corners(m, cu, id);
      for (int a = 0; a < nc; a++)
        if (mask >> a & 1u) {
          double v[4] = {share * N[a], wg[D * c] * N[a], wg[D * c + 1] * N[a], 0.0};
          if (D == 3)
            v[3] = wg[D * c + 2] * N[a];
          mpm_shape_in_list_add(id[a], D + 1, v, node, col, &cnt);
        }
    }
    return cnt;
  }
  double blk[BLOCK * BLOCK * BLOCK][4];
  for (int k = 0; k < bs[2]; k++)
    for (int j = 0; j < bs[1]; j++)
      for (int i = 0; i < bs[0]; i++)
        for (int l = 0; l < 4; l++)
          blk[i + BLOCK * (j + BLOCK * k)][l] = 0.0;
  /* slots of the unit corners 0 .. 2^D - 1 (corner order) from corner 0's */
  const int slot[8] = {0, 1, BLOCK + 1, BLOCK, BLOCK * BLOCK, BLOCK * BLOCK + 1,
                       BLOCK * BLOCK + BLOCK + 1, BLOCK * BLOCK + BLOCK};
  uint64_t used = 0;
  for (int c = 0; c < nc; c++) {
    double N[8];
    const int cu[3] = {ck[0][c], ck[1][c], ck[2][c]};
    const double cv[3] = {cl[0][c], cl[1][c], D == 3 ? cl[2][c] : 0.0};
    const unsigned mask = mpm_mesh_shape_corners(m, cu, cv, N);
    const double G[4] = {share, wg[D * c], wg[D * c + 1], D == 3 ? wg[D * c + 2] : 0.0};
    int at = dk[0][c] - lo[0] + BLOCK * (dk[1][c] - lo[1]);
    if (D == 3)
      at += BLOCK * BLOCK * (dk[2][c] - lo[2]);
    for (int a = 0; a < nc; a++) {
      if (!(mask >> a & 1u))
        continue;
      used |= (uint64_t)1 << (at + slot[a]);
      double *b = blk[at + slot[a]];
#pragma omp simd
      for (int l = 0; l < 4; l++)
        b[l] += G[l] * N[a];
    }
  }
  /* the used nodes along the axes from the last; on a periodic axis of few
   * units two of them can be one stored node: merged */
  int merge = 0;
  for (int d = 0; d < D; d++)
    merge |= m->periodic[d] && m->n[d] < bs[d];
  for (int k = 0; k < bs[2]; k++) {
    const int ks = D == 3 ? mpm_mesh_axis_node(uc[2] + lo[2] + k, m->nz, m->periodic_z) : 0;
    for (int j = 0; j < bs[1]; j++) {
      const int js = mpm_mesh_axis_node(uc[1] + lo[1] + j, m->ny, m->periodic_y);
      for (int i = 0; i < bs[0]; i++) {
        const int q = i + BLOCK * (j + BLOCK * k);
        if (!(used >> q & 1u))
          continue;
        const int id = (ks * m->sny + js) * m->snx +
                       mpm_mesh_axis_node(uc[0] + lo[0] + i, m->nx, m->periodic_x);
        if (merge) {
          mpm_shape_in_list_add(id, D + 1, blk[q], node, col, &cnt);
          continue;
        }
        node[cnt] = id;
        S[cnt] = blk[q][0];
        dS[0][cnt] = blk[q][1];
        dS[1][cnt] = blk[q][2];
        if (D == 3)
          dS[2][cnt] = blk[q][3];
        cnt++;
      }
    }
  }
  return cnt;
}

int mpm_shape_in_corner_general(const mpm_mesh *m, const double x[3], const double *r,
                                int *node, double *S, double *const dS[3])
{
  const mpm_mesh mc = *m;    /* a copy: no store through node, S, dS can change it */
  return mc.dim == 3 ? general(&mc, 3, x, r, node, S, dS) : general(&mc, 2, x, r, node, S, dS);
}

/* The slots [*k0, *k1] of an axis's factors A, B less the end ones whose A
 * and B are both 0 (never all: sum A = 1). */
static inline void axis_trim(const double *A, const double *B, int *k0, int *k1)
{
  while (*k0 < *k1 && A[*k0] == 0.0 && B[*k0] == 0.0)
    (*k0)++;
  while (*k1 > *k0 && A[*k1] == 0.0 && B[*k1] == 0.0)
    (*k1)--;
}

int mpm_shape_in_separable(const mpm_mesh *m, const double x[3], const int c[3],
                           const double h[3], mpm_shape_axes *ax)
{
  enum { W = MPM_SHAPE_AXIS_NODES };
  for (int d = 0; d < 3; d++) {
    if (d >= m->dim) {                         /* the plane's z: one factor 1 */
      ax->n[d] = 1;
      ax->idx[d][0] = 0;
      ax->A[d][0] = 1.0;
      ax->B[d][0] = 0.0;
      continue;
    }
    const double s[2] = {x[d] - h[d], x[d] + h[d]};
    int ck[2], dk[2];
    double cl[2];
    if (mpm_shape_in_corners_axis(2, s, m->o[d], m->len[d], m->ih[d], m->n[d], m->periodic[d],
                                  ck, cl))
      return -1;
    for (int q = 0; q < 2; q++) {
      dk[q] = mpm_mesh_axis_offset(ck[q] - c[d], m->n[d], m->periodic[d]);
      cl[q] = mpm_shape_in_snap(cl[q]);
    }
    const int lo = dk[0] < dk[1] ? dk[0] : dk[1];
    const int bs = (dk[0] < dk[1] ? dk[1] : dk[0]) - lo + 2;
    if (bs > W)
      return -2;
    double A[W], B[W];
    for (int k = 0; k < W; k++)
      A[k] = B[k] = 0.0;
    const double ib = 0.5 / h[d];
    for (int q = 0; q < 2; q++) {              /* corner -h (q = 0), +h (q = 1) */
      const int at = dk[q] - lo;
      const double phi[2] = {1.0 - cl[q], cl[q]}, sg = q ? ib : -ib;
      for (int a = 0; a < 2; a++) {
        A[at + a] += 0.5 * phi[a];
        B[at + a] += sg * phi[a];
      }
    }
    int k0 = 0, k1 = bs - 1;                   /* the end nodes of weight 0 left out */
    axis_trim(A, B, &k0, &k1);
    int cnt = 0;                               /* stored nodes; on a periodic axis of */
    for (int k = k0; k <= k1; k++) {           /* few units one can come twice: merged */
      const int id = mpm_mesh_axis_node(c[d] + lo + k, m->n[d], m->periodic[d]);
      int q = 0;
      while (q < cnt && ax->idx[d][q] != id)
        q++;
      if (q == cnt) {
        ax->idx[d][cnt] = id;
        ax->A[d][cnt] = A[k];
        ax->B[d][cnt] = B[k];
        cnt++;
      } else {
        ax->A[d][q] += A[k];
        ax->B[d][q] += B[k];
      }
    }
    ax->n[d] = cnt;
  }
  return 0;
}

/* The factorised weights along one axis of a batch of points whose two
 * corners x - h, x + h fall in units k0 and k0 + d1, d1 = 0, 1 or 2 (2
 * only by round-off, for a corner on a node), as the centre does: on a
 * non-periodic axis once clamped onto its faces; on a periodic one (of at
 * least d1 + 2 units, so that no two of the nodes are one) wrapped as
 * mpm_mesh_axis_wrap wraps them, a corner below the start then in unit -1
 * and one beyond the end in unit n. The sums of mpm_shape_in_separable
 * with corner 0 at slot 0 and corner 1 at slot d1, written without
 * branches (a loop that vectorises; its tests all of doubles): every value
 * bit for bit that function's. ok[i] is cleared for a point the case does
 * not cover. */
static inline __attribute__((always_inline)) void
axis_batch(double o, double len, double ih, int n, int per, const double *restrict x,
           const double *restrict r, int nb, int *restrict ok, int *restrict k0,
           int *restrict cnt, double (*restrict A)[BATCH], double (*restrict B)[BATCH])
{
  const double hi = o + len, end = n - 1, nd = n;
  for (int i = 0; i < nb; i++) {
    const double h = fabs(r[i]), ib = 0.5 / h;
    const double c = x[i] - o, s0 = x[i] - h, s1 = x[i] + h;
    double t0 = s0 - o, t1 = s1 - o, sa = 0.0, sb = 0.0;
    int in;
    if (per) {                               /* s mod len, floor(s / len) = -1, 0 or 1 */
      in = (c >= 0.0) & (c < len) & (t0 > -0.5 * len) & (t1 < 1.5 * len);
      const double w0 = t0 + len;
      const int below = (t0 < 0.0) & (w0 < len);   /* -tiny + len rounds to len: 0 */
      sa = below ? -nd : 0.0;
      t0 = t0 < 0.0 ? (below ? w0 : 0.0) : t0;
      sb = t1 >= len ? nd : 0.0;
      t1 = t1 >= len ? t1 - len : t1;
    } else {
      in = (x[i] >= o) & (x[i] <= hi);
      t0 = (s0 < o ? o : (s0 > hi ? hi : s0)) - o;
      t1 = (s1 < o ? o : (s1 > hi ? hi : s1)) - o;
      in &= (t0 == t0) & (t1 == t1);
    }
    double ka, kb, la, lb;                   /* units as doubles */
    mpm_mesh_axis_unit_real(in ? t0 : 0.0, ih, end, &ka, &la);
    mpm_mesh_axis_unit_real(in ? t1 : 0.0, ih, end, &kb, &lb);
    la = mpm_shape_in_snap(la);
    lb = mpm_shape_in_snap(lb);
    ka += sa;
    kb += sb;
    const double dk = kb - ka;
    in &= (dk >= 0.0) & (dk <= 2.0);
    if (per)
      in &= dk + 2.0 <= nd;                  /* no node twice */
    const double a0 = 0.5 * (1.0 - la), a1 = 0.5 * la, c0 = 0.5 * (1.0 - lb), c1 = 0.5 * lb;
    const double b0 = -ib * (1.0 - la), b1 = -ib * la, e0 = ib * (1.0 - lb), e1 = ib * lb;
    const int at0 = dk == 0.0, at1 = dk == 1.0, at2 = dk == 2.0;  /* corner 1's slot */
    const double a[4] = {(0.0 + a0) + (at0 ? c0 : 0.0), (0.0 + a1) + (at0 ? c1 : at1 ? c0 : 0.0),
                         0.0 + (at1 ? c1 : at2 ? c0 : 0.0), 0.0 + (at2 ? c1 : 0.0)};
    const double b[4] = {(0.0 + b0) + (at0 ? e0 : 0.0), (0.0 + b1) + (at0 ? e1 : at1 ? e0 : 0.0),
                         0.0 + (at1 ? e1 : at2 ? e0 : 0.0), 0.0 + (at2 ? e1 : 0.0)};
    /* the end slots of weight 0 left out (axis_trim): slot 0 (corner 0 at
     * l = 1) and slot dk + 1 (corner 1 at l = 0), never more */
    const double al = at0 ? a[1] : at1 ? a[2] : a[3], bl = at0 ? b[1] : at1 ? b[2] : b[3];
    const int lead = (a[0] == 0.0) & (b[0] == 0.0), trail = (al == 0.0) & (bl == 0.0);
    for (int k = 0; k < 4; k++) {
      A[k][i] = lead ? (k < 3 ? a[k + 1] : 0.0) : a[k];
      B[k][i] = lead ? (k < 3 ? b[k + 1] : 0.0) : b[k];
    }
    k0[i] = (int)(ka + (lead ? 1.0 : 0.0));
    cnt[i] = (int)(dk + (2.0 - (lead ? 1.0 : 0.0) - (trail ? 1.0 : 0.0)));
    ok[i] &= in;
  }
}

/* mpm_shape_in_separable_range in D = m->dim dimensions (a constant where
 * it is inlined). */
static inline __attribute__((always_inline)) long
separable_range(const mpm_mesh *m, int D, const mpm_points *pts, long lo, long hi,
                mpm_shape_stencil *st, int *fits)
{
  const mpm_mesh mc = *m;  /* a copy: no store through st can change it */
  long first = hi;
  for (long b = lo; b < hi; b += BATCH) {
    const int nb = hi - b < BATCH ? (int)(hi - b) : BATCH;
    int ok[BATCH], k0[3][BATCH], cnt[3][BATCH], row[BATCH];
    double A[3][MPM_SHAPE_AXIS_NODES][BATCH], B[3][MPM_SHAPE_AXIS_NODES][BATCH];
    /* an extent along the axes (mpm_shape_in_axes_extent's test) */
    for (int i = 0; i < nb; i++) {
      double v = 1.0, w = 0.0;
      int along = 1;
      for (int k = 0; k < D; k++) {
        const int k1 = (k + 1) % D;
        const double hk = fabs(pts->ext[k][k][b + i]), hn = fabs(pts->ext[k1][k1][b + i]);
        along &= hk != 0.0;
        v *= hk;
        w += D == 3 ? hk * hn : 0.0;
        for (int e = 0; e < D; e++)
          along &= e == k || pts->ext[k][e][b + i] == 0.0;
      }
      ok[i] = along & isfinite(v) & isfinite(w);
    }
    for (int d = 0; d < D; d++) {
      const double *x = pts->pos[d] + b, *r = pts->ext[d][d] + b;
      if (mc.periodic[d])
        axis_batch(mc.o[d], mc.len[d], mc.ih[d], mc.n[d], 1, x, r, nb, ok, k0[d], cnt[d], A[d],
                   B[d]);
      else
        axis_batch(mc.o[d], mc.len[d], mc.ih[d], mc.n[d], 0, x, r, nb, ok, k0[d], cnt[d], A[d],
                   B[d]);
    }
    {                                        /* the centres' units along the last axis */
      const double *x = pts->pos[D - 1] + b, o = mc.o[D - 1], ih = mc.ih[D - 1];
      const int n = mc.n[D - 1];
      for (int i = 0; i < nb; i++) {
        double v;
        mpm_mesh_axis_unit(ok[i] ? x[i] - o : 0.0, ih, n, &row[i], &v);
      }
    }
    for (int i = 0; i < nb; i++) {
      const long p = b + i;
      mpm_shape_axes *ax = &st->axes[p];
      if (ok[i]) {
        int nodes = 1;
        for (int d = 0; d < 3; d++) {
          if (d >= D) {                      /* the plane's z: one factor 1 */
            ax->n[d] = 1;
            ax->idx[d][0] = 0;
            ax->A[d][0] = 1.0;
            ax->B[d][0] = 0.0;
            continue;
          }
          ax->n[d] = cnt[d][i];
          for (int k = 0; k < MPM_SHAPE_AXIS_NODES; k++) {
            ax->idx[d][k] = mpm_mesh_axis_node(k0[d][i] + k, mc.n[d], mc.periodic[d]);
            ax->A[d][k] = A[d][k][i];
            ax->B[d][k] = B[d][k][i];
          }
          nodes *= ax->n[d];
        }
        st->count[p] = nodes;
        st->row[p] = row[i];
        continue;
      }
      /* the general case, point by point */
      double rr[9], h[3];
      mpm_shape_point_extent(pts, D, (size_t)p, rr);
      const double x[3] = {pts->x[p], pts->y[p], D == 3 ? pts->z[p] : 0.0};
      int c[3], count = -1;
      double l[3];
      if (!mpm_mesh_locate(&mc, x, c, l)) {
        if (!mpm_shape_in_axes_extent(D, rr, h)) {
          *fits = 0;
          return hi;
        }
        const int rc = mpm_shape_in_separable(&mc, x, c, h, ax);
        if (rc == -2) {
          *fits = 0;
          return hi;
        }
        count = rc ? -1 : ax->n[0] * ax->n[1] * ax->n[2];
      }
      if (mpm_shape_stencil_point(&mc, st, p, x[D - 1], count) < 0 && p < first)
        first = p;
    }
  }
  return first;
}

long mpm_shape_in_separable_range(const mpm_mesh *m, const mpm_points *pts, long lo, long hi,
                                  mpm_shape_stencil *st, int *fits)
{
  return m->dim == 3 ? separable_range(m, 3, pts, lo, hi, st, fits)
                     : separable_range(m, 2, pts, lo, hi, st, fits);
}

int mpm_shape_in_separable_list(const mpm_mesh *m, const mpm_shape_axes *ax, int *node,
                                double *S, double *const dS[3])
{
  const int D = m->dim;
  int cnt = 0;
  for (int k = 0; k < ax->n[2]; k++)
    for (int j = 0; j < ax->n[1]; j++) {
      const int row = (ax->idx[2][k] * m->sny + ax->idx[1][j]) * m->snx;
      for (int i = 0; i < ax->n[0]; i++) {
        double g[3];
        node[cnt] = row + ax->idx[0][i];
        S[cnt] = mpm_shape_axes_weight(ax, D, i, j, k, g);
        for (int d = 0; d < D; d++)
          dS[d][cnt] = g[d];
        cnt++;
      }
    }
  return cnt;
}
