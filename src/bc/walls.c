/* walls.c: outlets and staircase walls, on top of the edge mask of bc.c.
 *
 * An outlet is a stretch of one mesh edge that is a wall until it opens
 * (silo orifice, [DK15] section 4.2): two masks are kept, one with the
 * stretch closed and one with it free, and opening switches between them.
 * A sloped wall is a staircase of held nodes: every node inside or on a
 * polygon ([DK15] section 4.3); frictionless, the nodes along its sides hold
 * only the component normal to the side. */
#include "bc/bc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/config.h"

/* Mask bits of a wall of this kind whose normal is along x (nx_dir = 1) or y. */
static unsigned char wall_bits(int kind, int nx_dir)
{
  return mpm_bc_wall_bits(kind, nx_dir ? 0 : 1, 2);
}

static int edge_is_vertical(int e)
{
  return e == MPM_EDGE_LEFT || e == MPM_EDGE_RIGHT;
}

/* 1 if logical node (i, j) lies on edge e. */
static int on_edge(const mpm_mesh *m, int e, int i, int j)
{
  switch (e) {
  case MPM_EDGE_LEFT: return i == 0;
  case MPM_EDGE_RIGHT: return i == m->nx;
  case MPM_EDGE_BOTTOM: return j == 0;
  default: return j == m->ny;
  }
}

/* 1 if coordinate s along the edge (x on bottom/top, y on left/right) is in
 * the outlet [from, to] widened by `by` units at each end (to 1e-9 of a
 * unit; a negative `by` shrinks it). */
static int in_outlet_by(const mpm_bc *bc, const mpm_mesh *m, double s, double by)
{
  const double h = edge_is_vertical(bc->out_edge) ? m->dy : m->dx;
  return s >= bc->out_from - by * h && s <= bc->out_to + by * h;
}

/* 1 if s is in [from, to], ends included. */
static int in_outlet(const mpm_bc *bc, const mpm_mesh *m, double s)
{
  return in_outlet_by(bc, m, s, 1e-9);
}

/* 1 if node (i, j) of edge e, at coordinate s along it, is freed when the
 * outlet opens: in [from, to], or with held ends strictly inside it or at an
 * end on a perpendicular symmetry line (the mirror image of an inner node:
 * a half silo's orifice centre; mpm_bc_set_outlet). */
static int frees_node(const mpm_bc *bc, const mpm_mesh *m, int e, int i, int j, double s)
{
  if (!bc->out_held_ends || in_outlet_by(bc, m, s, -1e-9))
    return in_outlet(bc, m, s);
  if (!in_outlet(bc, m, s))
    return 0;
  if (edge_is_vertical(e))
    return (j == 0 && bc->edge[MPM_EDGE_BOTTOM] == MPM_BC_SYMMETRY) ||
           (j == m->ny && bc->edge[MPM_EDGE_TOP] == MPM_BC_SYMMETRY);
  return (i == 0 && bc->edge[MPM_EDGE_LEFT] == MPM_BC_SYMMETRY) ||
         (i == m->nx && bc->edge[MPM_EDGE_RIGHT] == MPM_BC_SYMMETRY);
}

int mpm_bc_set_outlet(mpm_bc *bc, const mpm_mesh *m, int e, double from, double to,
                      int closed, int held_ends, mpm_err *err)
{
  if (e < MPM_EDGE_LEFT || e > MPM_EDGE_TOP)
    return mpm_err_set(err, MPM_EINVAL, "outlet: unknown edge %d", e);
  if (closed != MPM_BC_NOSLIP && closed != MPM_BC_FRICTIONLESS)
    return mpm_err_set(err, MPM_EINVAL, "outlet: closed kind must be noslip or frictionless");
  if (!(to > from))
    return mpm_err_set(err, MPM_EINVAL, "outlet: extent (%g, %g) m is empty", from, to);
  if (bc->edge[e] == MPM_BC_PERIODIC)
    return mpm_err_set(err, MPM_EINVAL, "outlet: on a periodic edge");
  free(bc->mask[1]);
  bc->mask[1] = malloc((size_t)bc->nnodes);
  if (!bc->mask[1])
    return mpm_err_set(err, MPM_ENOMEM, "outlet mask: out of memory");
  memcpy(bc->mask[1], bc->mask[0], (size_t)bc->nnodes);
  bc->out_edge = e;
  bc->out_from = from;
  bc->out_to = to;
  bc->out_held_ends = held_ends != 0;
  const int vert = edge_is_vertical(e);
  for (int j = 0; j <= m->ny; j++)
    for (int i = 0; i <= m->nx; i++) {
      if (!on_edge(m, e, i, j))
        continue;
      double x, y;
      mpm_mesh_node_pos(m, i, j, &x, &y);
      if (!frees_node(bc, m, e, i, j, vert ? y : x))
        continue;
      const int id = mpm_mesh_node(m, i, j);
      /* open: only what a perpendicular edge meeting the outlet at a corner
       * asks (a symmetry line keeps its normal component); closed: that and
       * the outlet's own wall */
      unsigned char open_bits = 0;
      if (!vert && (i == 0 || i == m->nx))
        open_bits = wall_bits(bc->edge[i == 0 ? MPM_EDGE_LEFT : MPM_EDGE_RIGHT], 1);
      if (vert && (j == 0 || j == m->ny))
        open_bits = wall_bits(bc->edge[j == 0 ? MPM_EDGE_BOTTOM : MPM_EDGE_TOP], 0);
      bc->mask[1][id] = open_bits;
      bc->mask[0][id] = (unsigned char)(open_bits | wall_bits(closed, vert));
    }
  bc->fix = bc->open ? bc->mask[1] : bc->mask[0];
  return MPM_OK;
}

void mpm_bc_open_outlet(mpm_bc *bc)
{
  if (bc->mask[1]) {
    bc->open = 1;
    bc->fix = bc->mask[1];
  }
}

int mpm_bc_outlet_faces(const mpm_bc *bc, const mpm_mesh *m, int *lo, int *hi)
{
  *lo = *hi = 0;
  if (bc->out_edge < 0)
    return -1;
  const int vert = edge_is_vertical(bc->out_edge);
  const int n = vert ? m->ny : m->nx;
  const double h = vert ? m->dy : m->dx, s0 = vert ? m->y0 : m->x0;
  for (int k = 0; k < n; k++)                    /* unit face k: nodes k and k + 1 */
    if (in_outlet(bc, m, s0 + k * h) && in_outlet(bc, m, s0 + (k + 1) * h)) {
      if (*hi == 0)
        *lo = k;
      *hi = k + 1;
    }
  return bc->out_edge;
}

int mpm_bc_left_through_outlet(const mpm_bc *bc, const mpm_mesh *m, double x, double y)
{
  if (!bc->open || bc->out_edge < 0)
    return 0;
  const double xhi = m->x0 + m->lx, yhi = m->y0 + m->ly;
  switch (bc->out_edge) {
  case MPM_EDGE_LEFT: return x < m->x0 && y >= bc->out_from && y <= bc->out_to;
  case MPM_EDGE_RIGHT: return x > xhi && y >= bc->out_from && y <= bc->out_to;
  case MPM_EDGE_BOTTOM: return y < m->y0 && x >= bc->out_from && x <= bc->out_to;
  default: return y > yhi && x >= bc->out_from && x <= bc->out_to;
  }
}

/* Squared distance from (x, y) to segment a-b and the segment's unit normal. */
static double seg_dist2(double x, double y, double ax, double ay, double bx, double by,
                        double *nx, double *ny)
{
  const double ex = bx - ax, ey = by - ay, l2 = ex * ex + ey * ey;
  double t = l2 > 0.0 ? ((x - ax) * ex + (y - ay) * ey) / l2 : 0.0;
  t = t < 0.0 ? 0.0 : (t > 1.0 ? 1.0 : t);
  const double l = sqrt(l2);
  *nx = l > 0.0 ? -ey / l : 0.0;
  *ny = l > 0.0 ? ex / l : 0.0;
  const double dx = x - (ax + t * ex), dy = y - (ay + t * ey);
  return dx * dx + dy * dy;
}

/* Even-odd rule, as for fills. */
static int inside(int nv, const double *px, const double *py, double x, double y)
{
  int in = 0;
  for (int a = 0, b = nv - 1; a < nv; b = a++)
    if ((py[a] > y) != (py[b] > y) &&
        x < px[a] + (y - py[a]) * (px[b] - px[a]) / (py[b] - py[a]))
      in = !in;
  return in;
}

/* 1 when one of the (up to four) mesh units around node (i, j) is open: its
 * centre lies outside the polygon or on one of its sides. */
static int touches_open_unit(const mpm_mesh *m, int nv, const double *px, const double *py,
                             int i, int j, double tol)
{
  for (int uj = j - 1; uj <= j; uj++)
    for (int ui = i - 1; ui <= i; ui++) {
      if (ui < 0 || uj < 0 || ui >= m->nx || uj >= m->ny)
        continue;                                     /* beyond the mesh: no material */
      const double cx = m->x0 + (ui + 0.5) * m->dx, cy = m->y0 + (uj + 0.5) * m->dy;
      int on_side = 0;
      for (int a = 0, b = nv - 1; a < nv && !on_side; b = a++) {
        double sx, sy;
        on_side = seg_dist2(cx, cy, px[b], py[b], px[a], py[a], &sx, &sy) <= tol * tol;
      }
      if (on_side || !inside(nv, px, py, cx, cy))
        return 1;
    }
  return 0;
}

int mpm_bc_add_polygon(mpm_bc *bc, const mpm_mesh *m, int nv, const double *px,
                       const double *py, int kind, int *nheld, mpm_err *err)
{
  if (nv < 3)
    return mpm_err_set(err, MPM_EINVAL, "wall: %d vertices (needs at least 3)", nv);
  if (kind != MPM_BC_NOSLIP && kind != MPM_BC_FRICTIONLESS)
    return mpm_err_set(err, MPM_EINVAL, "wall: kind must be noslip or frictionless");
  const double tol = 1e-9 * fmin(m->dx, m->dy);
  int held = 0;
  for (int j = 0; j <= m->ny; j++)
    for (int i = 0; i <= m->nx; i++) {
      double x, y, best = INFINITY, nx = 0.0, ny = 0.0;
      mpm_mesh_node_pos(m, i, j, &x, &y);
      for (int a = 0, b = nv - 1; a < nv; b = a++) {
        double sx, sy, d2 = seg_dist2(x, y, px[b], py[b], px[a], py[a], &sx, &sy);
        if (d2 < best) {
          best = d2;
          nx = sx;
          ny = sy;
        }
      }
      if (!(best <= tol * tol || inside(nv, px, py, x, y)))
        continue;
      /* frictionless: a node at an open unit holds the normal component of
       * the nearest side, so points in the units along the side slide
       * parallel to it; the rest (and a side lying on the mesh edge, which no
       * open unit touches) is solid */
      const int id = mpm_mesh_node(m, i, j);
      unsigned char bits = MPM_FIX_X | MPM_FIX_Y;
      if (kind == MPM_BC_FRICTIONLESS && touches_open_unit(m, nv, px, py, i, j, tol)) {
        if (fabs(ny) <= 1e-12 * fabs(nx))
          bits = MPM_FIX_X;
        else if (fabs(nx) <= 1e-12 * fabs(ny))
          bits = MPM_FIX_Y;
        else {
          if (!bc->normal && !(bc->normal = calloc(2 * (size_t)bc->nnodes, sizeof *bc->normal)))
            return mpm_err_set(err, MPM_ENOMEM, "wall: no memory for node normals");
          bc->normal[2 * id] = nx;
          bc->normal[2 * id + 1] = ny;
          bits = MPM_FIX_N;
        }
      }
      bc->mask[0][id] |= bits;
      if (bc->mask[1])
        bc->mask[1][id] |= bits;
      held++;
    }
  if (nheld)
    *nheld = held;
  return MPM_OK;
}
