/* ugimp.c: uGIMP through the CPDI corner rule with a fixed extent
 * (MODEL.md section 3, [DK-silo] App. B).
 *
 * Corners x1 = xp - r1 - r2, x2 = xp + r1 - r2, x3 = xp + r1 + r2,
 * x4 = xp - r1 + r2;
 *   S_ip     = 1/4 sum_c N_i(x_c),
 *   gradS_ip = (1/A_p) { [N_i(x1) - N_i(x3)] (r1y - r2y, r2x - r1x)
 *                      + [N_i(x2) - N_i(x4)] (r1y + r2y, -r1x - r2x) },
 *   A_p = 4 (r1x r2y - r1y r2x), signed.
 * Corners beyond a non-periodic edge are clamped onto it (then the first-order
 * invariants hold only approximately there); periodic directions wrap through
 * the mesh basis. An extent of zero area falls back to the delta weights, the
 * limit of the rule as the extent shrinks. */
#include "shape/shape.h"

#include <math.h>
#include <string.h>

/* The merged node list of one point: node ids in the order first seen, and
 * an open-addressing table from id to list position, so that adding a
 * weight costs O(1) instead of a search of the list. The table has twice as
 * many slots as the list can hold, so probe chains stay short. */
enum { MERGE_BITS = 5, MERGE_SLOTS = 1 << MERGE_BITS };
_Static_assert(MERGE_SLOTS >= 2 * MPM_STENCIL_W, "merge table too small");

typedef struct merge_table {
  int id[MERGE_SLOTS];              /* node id, or -1 for a free slot */
  int at[MERGE_SLOTS];              /* its position in the list */
} merge_table;

/* Add weight (s, gx, gy) of storage node id to the merged list of *cnt nodes. */
static void merge_node(merge_table *t, int id, double s, double gx, double gy,
                       int *node, double *S, double *dSx, double *dSy, int *cnt)
{
  unsigned h = ((unsigned)id * 2654435761u) >> (32 - MERGE_BITS);  /* Fibonacci hash */
  while (t->id[h] != id && t->id[h] >= 0)
    h = (h + 1) % MERGE_SLOTS;
  if (t->id[h] < 0) {                                 /* first time: append */
    const int k = (*cnt)++;
    t->id[h] = id;
    t->at[h] = k;
    node[k] = id;
    S[k] = dSx[k] = dSy[k] = 0.0;
  }
  const int k = t->at[h];
  S[k] += s;
  dSx[k] += gx;
  dSy[k] += gy;
}

/* Move (x, y) onto the domain along non-periodic directions. */
static void clamp_corner(const mpm_mesh *m, double *x, double *y)
{
  if (!m->periodic_x) {
    double hi = m->x0 + m->lx;
    *x = *x < m->x0 ? m->x0 : (*x > hi ? hi : *x);
  }
  if (!m->periodic_y) {
    double hi = m->y0 + m->ly;
    *y = *y < m->y0 ? m->y0 : (*y > hi ? hi : *y);
  }
}

static int ugimp_eval(const mpm_mesh *m, double x, double y, const double r[4],
                      int *node, double *S, double *dSx, double *dSy)
{
  int iu, ju;
  if (mpm_mesh_unit(m, x, y, &iu, &ju) != MPM_OK)
    return -1;                               /* the centre decides */
  const double r1x = r[0], r1y = r[1], r2x = r[2], r2y = r[3];
  const double A = 4.0 * (r1x * r2y - r1y * r2x);  /* A_p, signed */
  if (A == 0.0)
    return mpm_mesh_basis(m, x, y, node, S, dSx, dSy);
  const double iA = 1.0 / A;
  /* corner offsets x_c - x_p, c = 1..4 */
  const double ox[4] = {-r1x - r2x, r1x - r2x, r1x + r2x, -r1x + r2x};
  const double oy[4] = {-r1y - r2y, r1y - r2y, r1y + r2y, -r1y + r2y};
  /* gradient weight of N(x_c): +a, +b, -a, -b with
   * a = (r1y - r2y, r2x - r1x)/A, b = (r1y + r2y, -r1x - r2x)/A */
  const double ax = (r1y - r2y) * iA, ay = (r2x - r1x) * iA;
  const double bx = (r1y + r2y) * iA, by = -(r1x + r2x) * iA;
  const double wx[4] = {ax, bx, -ax, -bx}, wy[4] = {ay, by, -ay, -by};
  merge_table t;
  memset(t.id, -1, sizeof t.id);
  int cnt = 0;
  for (int c = 0; c < 4; c++) {
    double cx = x + ox[c], cy = y + oy[c];
    clamp_corner(m, &cx, &cy);
    int id[4];
    double N[4], gx[4], gy[4];
    int k = mpm_mesh_basis(m, cx, cy, id, N, gx, gy);
    if (k < 0)
      return -1;                             /* non-finite extent */
    for (int a = 0; a < k; a++)              /* S += N/4, gradS += w_c N */
      merge_node(&t, id[a], 0.25 * N[a], wx[c] * N[a], wy[c] * N[a], node, S,
                 dSx, dSy, &cnt);
  }
  return cnt;
}

/* The corners of a point lie within hx = |r1x| + |r2x|, hy = |r1y| + |r2y|
 * of it. Along x they span 2 hx / dx units, so they fall in at most
 * floor(2 hx / dx) + 2 unit columns and touch one node column more; they
 * lie at most floor(hy / dy) + 1 unit rows from the point's own. (The small
 * slack covers round-off in the corner positions.) */
static void ugimp_span(const mpm_mesh *m, const mpm_points *pts, int *width, int *reach)
{
  double hx = 0.0, hy = 0.0;
  for (size_t p = 0; p < pts->n; p++) {
    const double ax = fabs(pts->r1x[p]) + fabs(pts->r2x[p]);
    const double ay = fabs(pts->r1y[p]) + fabs(pts->r2y[p]);
    hx = ax > hx ? ax : hx;
    hy = ay > hy ? ay : hy;
  }
  const double sx = 2.0 * hx * m->idx + 1e-6, sy = 2.0 * hy * m->idy + 1e-6;
  const int cols = sx < MPM_STENCIL_W ? (int)sx + 3 : MPM_STENCIL_W;  /* node columns */
  const int rows = sy < MPM_STENCIL_W ? (int)sy + 3 : MPM_STENCIL_W;
  *width = cols * rows < MPM_STENCIL_W ? cols * rows : MPM_STENCIL_W;
  *reach = 0.5 * sy < m->ny ? (int)(0.5 * sy) + 1 : m->ny;
}

const mpm_shape_type mpm_shape_ugimp = {
  .name = "ugimp",
  .description = "uGIMP, CPDI corner rule with a fixed parallelogram extent (r1, r2)",
  .eval = ugimp_eval,
  .span = ugimp_span,
  .at_point = 0,
};
