/* ugimp.c: the CPDI corner rule (MODEL.md section 3, [DK-silo] App. B; the
 * rule itself in corner.c): uGIMP, with the extent fixed as filled, and
 * CPDI1, the same rule with the extent convected by the deformation (the
 * step moves r1, r2 (, r3) with the point's velocity gradient:
 * mpm_shape_extent_convect_dim).
 *
 * A point's weights come from the general rule (mpm_shape_in_corner_general)
 * or, for an extent along the axes on boxes, from its factorised form
 * (mpm_shape_in_separable): the same sums regrouped, a few times fewer
 * operations.
 *
 * In the plane an extent along the mesh axes (r1 = (r1x, 0), r2 = (0, r2y):
 * every uGIMP point as filled) whose corners lie inside the mesh, neither
 * clamped nor wrapped, in one unit or two neighbours along each axis, takes
 * a faster path: its two corner columns and two corner rows located once,
 * for many points at a time (axes_locate, a loop that vectorises), then the
 * weights of the four possible unit blocks written out with the block in
 * registers (axes_sum, units_sum): the same values, bit for bit, as the
 * general rule, the two lists differing only in nodes of weights 0. On the
 * T3 silo of scripts/bench it takes a quarter of the general rule's
 * instructions. */
#include "shape/shape.h"

#include <math.h>

#include "shape/corners.h"

/* The corners of an extent along the axes fall in 1 x 1, 2 x 1, 1 x 2 or
 * 2 x 2 units (dx, dy = 0 or 1 more units along x, y): the weights of the
 * (dx + 2) x (dy + 2) nodes of those units, in row order, summed on a block
 * whose slots are known here (a + 3 b for node column a, row b), so that
 * with dx, dy constants the compiler keeps it in registers. Corner q lies in
 * unit (dx (q ^ q >> 1 & 1), dy (q >> 1)) at local (u[q ^ q >> 1 & 1],
 * v[q >> 1]) of a column cut along "/" if slash[...]; gradient weights
 * (-+ gx, -+ gy). A node inside the units or on their edges is always
 * listed, even if no corner's element holds it (a T3 unit's fourth
 * corner): its weights are then 0, which adds nothing where they are used;
 * on T3, an outer corner that may be in no triangle only if it weighs
 * something. diag: the mesh's diagonal rule (a constant). n0: storage id of
 * node (0, 0); no periodic seam inside the units. */
static inline __attribute__((always_inline)) int
units_sum(int dx, int dy, int ti, int diag, const int slash[2], const double u[2],
          const double v[2], double gx, double gy, int n0, int snx, int *node, double *S,
          double *dSx, double *dSy)
{
  typedef double rec __attribute__((vector_size(4 * sizeof(double))));  /* (S, gx, gy, 0) */
  rec blk[9];
  for (int k = 0; k < 9; k++)
    blk[k] = (rec){0.0, 0.0, 0.0, 0.0};
  const rec Gp = {0.25, gx, gy, 0.0};
#pragma GCC unroll 4
  for (int q = 0; q < 4; q++) {              /* corner order */
    const int sx = (q ^ q >> 1) & 1, sy = q >> 1;
    const int at = dx * sx + 3 * dy * sy;    /* slot of the unit's corner 0 */
    const int off[4] = {0, 1, 4, 3};         /* slots of unit corners 0..3 */
    const rec G = Gp * (rec){1.0, sx ? 1.0 : -1.0, sy ? 1.0 : -1.0, 1.0};   /* exact */
    double N[4];
    mpm_mesh_shape_unit(ti, slash[sx], u[sx], v[sy], N);
#pragma GCC unroll 4
    for (int a = 0; a < 4; a++)
      blk[at + off[a]] += G * N[a];
  }
  int cnt = 0;
#pragma GCC unroll 3
  for (int b = 0; b < dy + 2; b++)
#pragma GCC unroll 3
    for (int a = 0; a < dx + 2; a++) {
      const rec w = blk[a + 3 * b];
      node[cnt] = n0 + a + b * snx;
      S[cnt] = w[0];
      dSx[cnt] = w[1];
      dSy[cnt] = w[2];
      /* an outer corner of the units is unit corner q of one unit; on T3 it
       * may be in neither of its triangles (corners 1 and 3 of a "/" unit,
       * 0 and 2 of a "\" one): then it stays listed only if it weighs
       * something (N >= 0, so S = 0 only if every N of it is 0, and then
       * gradS = 0 too) */
      const int outer = (a == 0 || a == dx + 1) && (b == 0 || b == dy + 1);
      const int q = (a > 0) + 3 * (b > 0) - 2 * (a > 0 && b > 0);
      const int may = ti == MPM_TOPO_T3 && outer &&
                      (diag == MPM_DIAG_MIRROR || (diag == MPM_DIAG_SLASH) == (q & 1));
      cnt += may ? w[0] != 0.0 : 1;
    }
  return cnt;
}

/* The mesh along the four corner lanes of axes_locate: the corner columns
 * (x - r1x, x + r1x) and rows (y - r2y, y + r2y). */
typedef struct lanes {
  double o[4], len[4], hi[4], ih[4];
  int n[4];
  int last[2];  /* highest second corner column, row: no periodic seam in the block */
} lanes;

static inline void lanes_of(const mpm_mesh *m, lanes *L)
{
  for (int l = 0; l < 4; l++) {
    const int y = l >= 2;
    L->o[l] = y ? m->y0 : m->x0;
    L->len[l] = y ? m->ly : m->lx;
    L->hi[l] = L->o[l] + L->len[l];
    L->ih[l] = y ? m->idy : m->idx;
    L->n[l] = y ? m->ny : m->nx;
  }
  L->last[0] = m->periodic_x ? m->nx - 2 : m->nx;
  L->last[1] = m->periodic_y ? m->ny - 2 : m->ny;
}

/* An extent along the axes, r = (r1x, 0, 0, r2y) (every uGIMP point as
 * filled: r1x, r2y > 0), its corners inside the mesh, in one unit or two
 * neighbours in order along each axis: corner columns x - r1x, x + r1x,
 * rows y - r2y, y + r2y (corner c on column side (c ^ c >> 1) & 1 and row
 * side c >> 1, corners.h), each located once (unit k[l], local t[l], lanes
 * l = 0 .. 3 as in `lanes`), without clamping or wrapping; the centre lies
 * between them, inside the mesh, in unit row *row. With the gradient
 * weights g = (r2y / A, r1x / A), A = 4 r1x r2y. Returns the class
 * dx + 2 dy (dx, dy = 0 or 1 more units along x, y; a negative extent in
 * one unit passes as 0), or -1 when the case does not apply (another
 * extent, a corner outside, corners more than a unit apart or in reverse
 * order, a periodic seam among the nodes). Branch-free, for a loop over
 * points that vectorises. */
static inline __attribute__((always_inline)) int
axes_locate(const lanes *L, double x, double y, const double r[4], int k[4], double t[4],
            double g[2], int *row)
{
  const double A = 4.0 * (r[0] * r[3]), iA = 1.0 / A;
  const double c[4] = {x - r[0], x + r[0], y - r[3], y + r[3]};
  int out = !(r[1] == 0.0) | !(r[2] == 0.0) | !(fabs(A) > 0.0) | !(fabs(A) < HUGE_VAL);
#pragma GCC unroll 4
  for (int l = 0; l < 4; l++) {              /* unclamped, unwrapped (corners.h) */
    const double s = c[l] - L->o[l];
    out |= !(s >= 0.0) | !(s < L->len[l]) | !(c[l] <= L->hi[l]);
    /* located inside the axis, whatever s (NaN: 0), so the conversion to
     * int is defined; that changes nothing where out stays 0 */
    mpm_mesh_axis_unit(s > 0.0 ? (s < L->len[l] ? s : L->len[l]) : 0.0, L->ih[l], L->n[l], &k[l],
                       &t[l]);
  }
  const int dx = k[1] - k[0], dy = k[3] - k[2];
  out |= ((unsigned)dx > 1u) | ((unsigned)dy > 1u) | (k[1] > L->last[0]) | (k[3] > L->last[1]);
  g[0] = r[3] * iA;                          /* w_c = (-+ g[0], -+ g[1]) */
  g[1] = r[0] * iA;
  double v;
  const double sy = y - L->o[2];             /* the centre's row (clamped as the corners) */
  mpm_mesh_axis_unit(sy > 0.0 ? (sy < L->len[2] ? sy : L->len[2]) : 0.0, L->ih[2], L->n[2], row,
                     &v);
  return out ? -1 : dx + 2 * dy;
}

/* The weights of a point located by axes_locate (class cls >= 0, units k,
 * local positions t, gradient weights g): the rule's sums with
 * r1y = r2x = 0 reduce exactly to A = 4 r1x r2y and
 * w_c = (-+ r2y / A, -+ r1x / A) (its products with 0 add nothing but a
 * sign of zero), so every weight is the general path's bit for bit; the
 * lists differ only in nodes of weights 0 (units_sum). ti, diag: the
 * mesh's topology and diagonal rule (constants where the caller
 * specialises on them). Returns the node count. */
static inline __attribute__((always_inline)) int
axes_sum(const mpm_mesh *m, int ti, int diag, int cls, const int k[4], const double t[4],
         const double g[2], int *node, double *S, double *dSx, double *dSy)
{
  const double gx = g[0], gy = g[1];
  const int t3 = ti == MPM_TOPO_T3, mirror = diag == MPM_DIAG_MIRROR, sl = diag == MPM_DIAG_SLASH;
  const int slash[2] = {t3 && (mirror ? mpm_mesh_column_is_slash(m, k[0]) : sl),
                        t3 && (mirror ? mpm_mesh_column_is_slash(m, k[1]) : sl)};
  const double u[2] = {t[0], t[1]}, v[2] = {t[2], t[3]};
  const int n0 = k[2] * m->snx + k[0], snx = m->snx;
  switch (cls) {                             /* dx, dy as constants */
  case 0:
    return units_sum(0, 0, ti, diag, slash, u, v, gx, gy, n0, snx, node, S, dSx, dSy);
  case 1:
    return units_sum(1, 0, ti, diag, slash, u, v, gx, gy, n0, snx, node, S, dSx, dSy);
  case 2:
    return units_sum(0, 1, ti, diag, slash, u, v, gx, gy, n0, snx, node, S, dSx, dSy);
  default:
    return units_sum(1, 1, ti, diag, slash, u, v, gx, gy, n0, snx, node, S, dSx, dSy);
  }
}

static int ugimp_eval(const mpm_mesh *mesh, const double x[3], const double *r, int *node,
                      double *S, double *const dS[3])
{
  const mpm_mesh mc = *mesh;  /* a copy: no store through node, S, dS can change it */
  if (mc.dim == 2) {
    lanes L;
    lanes_of(&mc, &L);
    int k[4], row;
    double t[4], g[2];
    const int cls = axes_locate(&L, x[0], x[1], r, k, t, g, &row);
    if (cls >= 0)
      return axes_sum(&mc, mc.topology, mc.diagonal, cls, k, t, g, node, S, dS[0], dS[1]);
  } else {
    double h[3];
    int c[3];
    double l[3];
    if (mpm_mesh_locate(&mc, x, c, l))
      return -1;                               /* the centre decides */
    mpm_shape_axes ax;
    if (mpm_shape_in_axes_extent(3, r, h)) {   /* along the axes: a box */
      const int rc = mpm_shape_in_separable(&mc, x, c, h, &ax);
      if (rc == -1)
        return -1;
      if (rc == 0)
        return mpm_shape_in_separable_list(&mc, &ax, node, S, dS);
    }
  }
  return mpm_shape_in_corner_general(&mc, x, r, node, S, dS);
}

/* The points [lo, hi) (mpm_shape_type.fill's contract), for topology ti
 * and diagonal rule diag, in batches: first every point of a batch located
 * (a loop across points that vectorises), then each one's weights. */
static inline __attribute__((always_inline)) long
fill_range(const mpm_mesh *m, const lanes *L, int ti, int diag, const mpm_points *pts, long lo,
           long hi, mpm_shape_stencil *st)
{
  enum { BATCH = 64 };
  const size_t w = (size_t)st->w;
  const double *const px = pts->x, *const py = pts->y;
  const double *const r1x = pts->r1x, *const r1y = pts->r1y, *const r2x = pts->r2x,
               *const r2y = pts->r2y;
  const lanes Lc = *L;
  long first = hi;
  for (long b = lo; b < hi; b += BATCH) {
    const int nb = hi - b < BATCH ? (int)(hi - b) : BATCH;
    int kb[4][BATCH], cls[BATCH], rowb[BATCH];
    double tb[4][BATCH], gb[2][BATCH];
    /* a loop that vectorises (not omp simd: its private arrays would stop it) */
    for (int i = 0; i < nb; i++) {
      const long p = b + i;
      const double r[4] = {r1x[p], r1y[p], r2x[p], r2y[p]};
      int k[4];
      double t[4], g[2];
      cls[i] = axes_locate(&Lc, px[p], py[p], r, k, t, g, &rowb[i]);
#pragma GCC unroll 4
      for (int l = 0; l < 4; l++) {
        kb[l][i] = k[l];
        tb[l][i] = t[l];
      }
      gb[0][i] = g[0];
      gb[1][i] = g[1];
    }
    for (int i = 0; i < nb; i++) {
      const long p = b + i;
      const size_t o = (size_t)p * w;
      if (cls[i] >= 0) {
        const int k[4] = {kb[0][i], kb[1][i], kb[2][i], kb[3][i]};
        const double t[4] = {tb[0][i], tb[1][i], tb[2][i], tb[3][i]};
        const double g[2] = {gb[0][i], gb[1][i]};
        st->count[p] = axes_sum(m, ti, diag, cls[i], k, t, g, st->node + o, st->S + o,
                                st->dS[0] + o, st->dS[1] + o);
        st->row[p] = rowb[i];
        continue;
      }
      const double r[4] = {r1x[p], r1y[p], r2x[p], r2y[p]};
      const double x[3] = {px[p], py[p], 0.0};
      double *const dS[3] = {st->dS[0] + o, st->dS[1] + o, NULL};
      const int c = mpm_shape_in_corner_general(m, x, r, st->node + o, st->S + o, dS);
      if (mpm_shape_stencil_point(m, st, p, py[p], c) < 0 && p < first)
        first = p;
    }
  }
  return first;
}

static long ugimp_fill(const mpm_mesh *mesh, const mpm_points *pts, long lo, long hi,
                       mpm_shape_stencil *st)
{
  const mpm_mesh mc = *mesh;
  lanes L;
  lanes_of(&mc, &L);
  if (mc.topology == MPM_TOPO_Q4)
    return fill_range(&mc, &L, MPM_TOPO_Q4, MPM_DIAG_SLASH, pts, lo, hi, st);
  switch (mc.diagonal) {
  case MPM_DIAG_SLASH:
    return fill_range(&mc, &L, MPM_TOPO_T3, MPM_DIAG_SLASH, pts, lo, hi, st);
  case MPM_DIAG_BACKSLASH:
    return fill_range(&mc, &L, MPM_TOPO_T3, MPM_DIAG_BACKSLASH, pts, lo, hi, st);
  default:
    return fill_range(&mc, &L, MPM_TOPO_T3, MPM_DIAG_MIRROR, pts, lo, hi, st);
  }
}

/* The corners of a point lie within h_d = sum_k |r_kd| of it along axis d;
 * the nodes they touch and, along the last axis, the units they reach
 * follow per axis (mpm_shape_in_span_axis), from the largest h_d of the
 * points. */
static void ugimp_span(const mpm_mesh *m, const mpm_points *pts, int *width, int *reach)
{
  const int D = m->dim, cap = mpm_shape_width_cap(D);
  const size_t n = pts->n;
  double h[3] = {0.0, 0.0, 0.0};
  for (int d = 0; d < D; d++) {
    const double *const r0 = pts->ext[0][d], *const r1 = pts->ext[1][d];
    const double *const r2 = D == 3 ? pts->ext[2][d] : NULL;
    double hd = 0.0;
    if (D == 3) {
#pragma omp simd reduction(max : hd)
      for (size_t p = 0; p < n; p++) {
        const double a = fabs(r0[p]) + fabs(r1[p]) + fabs(r2[p]);
        hd = a > hd ? a : hd;
      }
    } else {
#pragma omp simd reduction(max : hd)
      for (size_t p = 0; p < n; p++) {
        const double a = fabs(r0[p]) + fabs(r1[p]);
        hd = a > hd ? a : hd;
      }
    }
    h[d] = hd;
  }
  int w = 1, re = 0;
  for (int d = 0; d < D; d++) {
    int nd, rd;
    mpm_shape_in_span_axis(h[d], m->ih[d], m->n[d], cap, &nd, &rd);
    w = w < cap ? w * nd : cap;                              /* nodes along the axes */
    re = rd;                                                 /* the last axis' */
  }
  *width = w < cap ? w : cap;
  *reach = re;
}

const mpm_shape_type mpm_shape_ugimp = {
  .name = "ugimp",
  .description = "uGIMP, CPDI corner rule with a fixed extent (r1, r2, r3 in 3D) as filled",
  .eval = ugimp_eval,
  .fill = ugimp_fill,
  .span = ugimp_span,
  .at_point = 0,
  .convect = 0,
  .separable = 1,
};

const mpm_shape_type mpm_shape_cpdi = {
  .name = "cpdi",
  .description = "CPDI1, the corner rule with the extent convected by the deformation",
  .eval = ugimp_eval,
  .fill = ugimp_fill,
  .span = ugimp_span,
  .at_point = 0,
  .convect = 1,
};
