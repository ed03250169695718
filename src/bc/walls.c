/* walls.c: outlets and staircase walls, on top of the face mask of bc.c,
 * for a mesh of either dimension.
 *
 * An outlet is a stretch of one face that is a wall until it opens (a silo
 * orifice, [DK15] section 4.2): a (D-1)-box (the plane's interval of an
 * edge, a rectangle of a box's face) or a disc, in the coordinates along
 * the face. Two masks are kept, one with the stretch closed and one with it
 * free, and opening switches between them.
 * A sloped wall is a staircase of held nodes: every node inside or on a
 * polygon ([DK15] section 4.3), in 3D the prism along z of it; frictionless,
 * the nodes along its sides hold only the component normal to the side. */
#include "bc/bc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/config.h"

int mpm_bc_face_axes(int dim, int f, int axes[2])
{
  const int n = f / 2;
  if (dim == 2) {
    axes[0] = n == 0 ? 1 : 0;
    return 1;
  }
  axes[0] = n == 0 ? 1 : 0;
  axes[1] = n == 2 ? 1 : 2;
  return 2;
}

/* 1 if logical node c lies on face f. */
static int on_face(const mpm_mesh *m, int f, const int c[3])
{
  return c[f / 2] == (f % 2 ? m->n[f / 2] : 0);
}

/* Union of the masks of the faces through logical node c, face `skip` left
 * out (-1: none). */
static unsigned char node_bits(const mpm_bc *bc, const mpm_mesh *m, const int c[3], int skip)
{
  unsigned char b = 0;
  for (int f = 0; f < 2 * m->dim; f++)
    if (f != skip && on_face(m, f, c))
      b |= mpm_bc_wall_bits(bc->face[f], f / 2, m->dim);
  return b;
}

/* 1 if the point s (in the outlet face's axes, na of them) lies in the
 * outlet, boundary included to tol (a negative tol: strictly inside). */
static int in_outlet(const mpm_bc *bc, int na, const double s[2], double tol)
{
  if (bc->out_shape == MPM_BC_OUTLET_DISC) {
    const double a = s[0] - bc->out_c[0], b = s[1] - bc->out_c[1], r = bc->out_r + tol;
    return a * a + b * b <= r * r;
  }
  for (int d = 0; d < na; d++)
    if (s[d] < bc->out_lo[d] - tol || s[d] > bc->out_hi[d] + tol)
      return 0;
  return 1;
}

/* 1 if node c of the outlet's face, at s in the face's axes ax, is freed
 * when the outlet opens: in it (to tol), or with held ends strictly inside
 * it, or on a box's side that lies on a symmetry face (the mirror image of
 * an inner node: the orifice's centre line in a half or quarter silo); a
 * node at a corner is freed when each of its sides is. A disc's boundary is
 * its arc: a node on a symmetry face inside the arc is strictly inside. */
static int frees_node(const mpm_bc *bc, const mpm_mesh *m, const int c[3], int na,
                      const int ax[2], const double s[2], double tol)
{
  if (!in_outlet(bc, na, s, tol))
    return 0;
  if (!bc->out_held || in_outlet(bc, na, s, -tol))
    return 1;
  if (bc->out_shape == MPM_BC_OUTLET_DISC)
    return 0;
  for (int d = 0; d < na; d++) {
    if (s[d] > bc->out_lo[d] + tol && s[d] < bc->out_hi[d] - tol)
      continue;                                          /* inside along this axis */
    const int side = 2 * ax[d] + (s[d] >= bc->out_hi[d] - tol);   /* the face at that end */
    if (!on_face(m, side, c) || bc->face[side] != MPM_BC_SYMMETRY)
      return 0;
  }
  return 1;
}

/* The tolerance of "on the outlet's boundary" on face f: 1e-9 of the
 * smaller unit size along it. */
static double outlet_tol(const mpm_mesh *m, int f)
{
  int ax[2] = {0, 0};
  const int na = mpm_bc_face_axes(m->dim, f, ax);
  double h = m->h[ax[0]];
  if (na == 2 && m->h[ax[1]] < h)
    h = m->h[ax[1]];
  return 1e-9 * h;
}

int mpm_bc_set_outlet(mpm_bc *bc, const mpm_mesh *m, int f, int shape, const double lo[2],
                      const double hi[2], int closed, int held_ends, mpm_err *err)
{
  if (!bc->mask[0])
    return mpm_err_set(err, MPM_EINVAL, "outlet: boundary not set up");
  if (f < 0 || f >= 2 * m->dim)
    return mpm_err_set(err, MPM_EINVAL, "outlet: unknown face %d", f);
  if (closed != MPM_BC_NOSLIP && closed != MPM_BC_FRICTIONLESS)
    return mpm_err_set(err, MPM_EINVAL, "outlet: closed kind must be noslip or frictionless");
  if (bc->face[f] == MPM_BC_PERIODIC)
    return mpm_err_set(err, MPM_EINVAL, "outlet: on a periodic face");
  int ax[2] = {0, 0};
  const int na = mpm_bc_face_axes(m->dim, f, ax);
  if (shape == MPM_BC_OUTLET_DISC && na != 2)
    return mpm_err_set(err, MPM_EINVAL, "outlet: a disc on a plane edge");
  for (int d = 0; d < na; d++)
    if (!(hi[d] > lo[d]))
      return mpm_err_set(err, MPM_EINVAL, "outlet: extent (%g, %g) m is empty", lo[d], hi[d]);
  const double r = 0.5 * (hi[0] - lo[0]);
  if (shape == MPM_BC_OUTLET_DISC && !(r < 1e300))
    return mpm_err_set(err, MPM_EINVAL, "outlet: disc radius %g m must be finite", r);
  unsigned char *open = malloc((size_t)bc->nnodes);
  if (!open)
    return mpm_err_set(err, MPM_ENOMEM, "outlet mask: out of memory");
  free(bc->mask[1]);
  bc->mask[1] = open;
  bc->out_face = f;
  bc->out_shape = shape;
  bc->out_held = held_ends != 0;
  for (int d = 0; d < na; d++) {
    bc->out_lo[d] = lo[d];
    bc->out_hi[d] = hi[d];
    bc->out_c[d] = 0.5 * (lo[d] + hi[d]);
  }
  bc->out_r = r;
  /* the faces' mask again (a second outlet replaces the first) */
  const int kz = m->dim == 3 ? m->nz : 0;
  int c[3];
  for (c[2] = 0; c[2] <= kz; c[2]++)
    for (c[1] = 0; c[1] <= m->ny; c[1]++)
      for (c[0] = 0; c[0] <= m->nx; c[0]++)
        bc->mask[0][mpm_mesh_node(m, c[0], c[1], c[2])] = 0;
  for (c[2] = 0; c[2] <= kz; c[2]++)
    for (c[1] = 0; c[1] <= m->ny; c[1]++)
      for (c[0] = 0; c[0] <= m->nx; c[0]++)
        bc->mask[0][mpm_mesh_node(m, c[0], c[1], c[2])] |= node_bits(bc, m, c, -1);
  memcpy(open, bc->mask[0], (size_t)bc->nnodes);
  /* the outlet's nodes: closed, the other faces' bits and the closed wall's;
   * open, only the other faces' */
  const double tol = outlet_tol(m, f);
  const unsigned char wall = mpm_bc_wall_bits(closed, f / 2, m->dim);
  for (c[2] = 0; c[2] <= kz; c[2]++)
    for (c[1] = 0; c[1] <= m->ny; c[1]++)
      for (c[0] = 0; c[0] <= m->nx; c[0]++) {
        if (!on_face(m, f, c))
          continue;
        double x[3];
        mpm_mesh_node_pos(m, c[0], c[1], c[2], x);
        const double s[2] = {x[ax[0]], na == 2 ? x[ax[1]] : 0.0};
        if (!frees_node(bc, m, c, na, ax, s, tol))
          continue;                  /* held ends: the boundary's nodes keep the face's */
        const int id = mpm_mesh_node(m, c[0], c[1], c[2]);
        const unsigned char others = node_bits(bc, m, c, f);
        open[id] = others;
        bc->mask[0][id] = (unsigned char)(others | wall);
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

int mpm_bc_outlet_face_open(const mpm_bc *bc, const mpm_mesh *m, const int c[3])
{
  if (bc->out_face < 0)
    return 0;
  int ax[2] = {0, 0};
  const int na = mpm_bc_face_axes(m->dim, bc->out_face, ax);
  const double tol = outlet_tol(m, bc->out_face);
  for (int k = 0; k < 1 << na; k++) {          /* the corners of the unit's face */
    double s[2] = {0.0, 0.0};
    for (int d = 0; d < na; d++)
      s[d] = m->o[ax[d]] + (c[ax[d]] + (k >> d & 1)) * m->h[ax[d]];
    if (!in_outlet(bc, na, s, tol))
      return 0;
  }
  return 1;
}

int mpm_bc_outlet_faces(const mpm_bc *bc, const mpm_mesh *m, int lo[3], int hi[3])
{
  for (int a = 0; a < 3; a++)
    lo[a] = hi[a] = 0;
  if (bc->out_face < 0)
    return -1;
  const int f = bc->out_face;
  int ax[2] = {0, 0};
  const int na = mpm_bc_face_axes(m->dim, f, ax);
  const int n1 = na == 2 ? m->n[ax[1]] : 1;
  int first = 1;
  for (int v = 0; v < n1; v++)
    for (int u = 0; u < m->n[ax[0]]; u++) {
      int c[3] = {0, 0, 0};
      c[ax[0]] = u;
      if (na == 2)
        c[ax[1]] = v;
      if (!mpm_bc_outlet_face_open(bc, m, c))
        continue;
      for (int k = 0; k < na; k++) {
        const int a = ax[k];
        lo[a] = first || c[a] < lo[a] ? c[a] : lo[a];
        hi[a] = first || c[a] + 1 > hi[a] ? c[a] + 1 : hi[a];
      }
      first = 0;
    }
  if (!first)
    for (int a = 0; a < 3; a++)
      if (a == f / 2 || a >= m->dim) {         /* across the face, the plane's z: all */
        lo[a] = 0;
        hi[a] = m->n[a];
      }
  return f;
}

int mpm_bc_left_through_outlet(const mpm_bc *bc, const mpm_mesh *m, const double x[3])
{
  if (!bc->open || bc->out_face < 0)
    return 0;
  const int f = bc->out_face, d = f / 2;
  if (f % 2 ? !(x[d] > m->o[d] + m->len[d]) : !(x[d] < m->o[d]))
    return 0;                                  /* not beyond the outlet's face */
  int ax[2] = {0, 0};
  const int na = mpm_bc_face_axes(m->dim, f, ax);
  const double s[2] = {x[ax[0]], na == 2 ? x[ax[1]] : 0.0};
  return in_outlet(bc, na, s, 0.0);
}

/* ---- staircase walls ---------------------------------------------------------- */

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

/* 1 when one of the (up to four) x-y units around node column (i, j) is
 * open: its centre lies outside the polygon or on one of its sides. */
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
  if (!bc->mask[0])
    return mpm_err_set(err, MPM_EINVAL, "wall: boundary not set up");
  if (nv < 3)
    return mpm_err_set(err, MPM_EINVAL, "wall: %d vertices (needs at least 3)", nv);
  if (kind != MPM_BC_NOSLIP && kind != MPM_BC_FRICTIONLESS)
    return mpm_err_set(err, MPM_EINVAL, "wall: kind must be noslip or frictionless");
  const double tol = 1e-9 * fmin(m->dx, m->dy);
  const int kz = m->dim == 3 ? m->nz : 0;
  int held = 0;
  for (int j = 0; j <= m->ny; j++)
    for (int i = 0; i <= m->nx; i++) {
      double x[3], best = INFINITY, nx = 0.0, ny = 0.0;
      mpm_mesh_node_pos(m, i, j, 0, x);
      for (int a = 0, b = nv - 1; a < nv; b = a++) {
        double sx, sy, d2 = seg_dist2(x[0], x[1], px[b], py[b], px[a], py[a], &sx, &sy);
        if (d2 < best) {
          best = d2;
          nx = sx;
          ny = sy;
        }
      }
      if (!(best <= tol * tol || inside(nv, px, py, x[0], x[1])))
        continue;
      /* frictionless: a node at an open unit holds the normal component of
       * the nearest side, so points in the units along the side slide
       * parallel to it; the rest (and a side lying on the mesh edge, which no
       * open unit touches) is solid, and held along z too */
      unsigned char bits = MPM_FIX_X | MPM_FIX_Y | (m->dim == 3 ? MPM_FIX_Z : 0);
      int oblique = 0;
      if (kind == MPM_BC_FRICTIONLESS && touches_open_unit(m, nv, px, py, i, j, tol)) {
        if (fabs(ny) <= 1e-12 * fabs(nx))
          bits = MPM_FIX_X;
        else if (fabs(nx) <= 1e-12 * fabs(ny))
          bits = MPM_FIX_Y;
        else {
          if (!bc->normal && !(bc->normal = calloc(2 * (size_t)bc->nnodes, sizeof *bc->normal)))
            return mpm_err_set(err, MPM_ENOMEM, "wall: no memory for node normals");
          bits = MPM_FIX_N;
          oblique = 1;
        }
      }
      for (int k = 0; k <= kz; k++) {
        const int id = mpm_mesh_node(m, i, j, k);
        bc->mask[0][id] |= bits;
        if (bc->mask[1])
          bc->mask[1][id] |= bits;
        if (oblique) {
          bc->normal[2 * id] = nx;
          bc->normal[2 * id + 1] = ny;
        }
        held += k < m->nz || !m->periodic_z;      /* an aliased layer once */
      }
    }
  if (nheld)
    *nheld = held;
  return MPM_OK;
}
