/* bc3.c: face boundary conditions of the 3D mesh of boxes as a per-node mask,
 * and outlets (rectangles, discs) on a face. The kinds, the kind-to-mask rule
 * and the periodic checks are those of the 2D edges (bc.c). */
#include "bc/bc3.h"

#include <stdlib.h>
#include <string.h>

#include "bc/bc_internal.h"
#include "core/config.h"
#include "mesh/mesh.h"

static const char *const face_names[] = {"-x", "+x", "-y", "+y", "-z", "+z"};

void mpm_bc3_face_axes(int f, int axes[2])
{
  const int n = f / 2;
  axes[0] = n == 0 ? 1 : 0;
  axes[1] = n == 2 ? 1 : 2;
}

/* 1 if logical node ijk lies on face f. */
static int on_face(const mpm_mesh3 *m, int f, const int ijk[3])
{
  const int n[3] = {m->nx, m->ny, m->nz};
  return ijk[f / 2] == (f % 2 ? n[f / 2] : 0);
}

/* Union of the masks of the faces through logical node ijk, face `skip`
 * left out (-1: none). */
static unsigned char node_bits(const mpm_bc3 *bc, const mpm_mesh3 *m, const int ijk[3], int skip)
{
  unsigned char b = 0;
  for (int f = 0; f < 6; f++)
    if (f != skip && on_face(m, f, ijk))
      b |= mpm_bc_wall_bits(bc->face[f], f / 2, 3);
  return b;
}

/* The faces' mask into mask[nnodes], over logical nodes: an aliased node
 * gets the bits of both its copies, none from a periodic face. */
static void face_mask(const mpm_bc3 *bc, const mpm_mesh3 *m, unsigned char *mask)
{
  memset(mask, 0, (size_t)bc->nnodes);
  int ijk[3];
  for (ijk[2] = 0; ijk[2] <= m->nz; ijk[2]++)
    for (ijk[1] = 0; ijk[1] <= m->ny; ijk[1]++)
      for (ijk[0] = 0; ijk[0] <= m->nx; ijk[0]++)
        mask[mpm_mesh3_node(m, ijk[0], ijk[1], ijk[2])] |= node_bits(bc, m, ijk, -1);
}

int mpm_bc3_setup(mpm_bc3 *bc, const mpm_mesh3 *m, const int face[6], mpm_err *err)
{
  const int periodic[3] = {m->periodic_x, m->periodic_y, m->periodic_z};
  int rc = mpm_bc_check_kinds(face, 3, periodic, face_names, "faces", err);
  if (rc != MPM_OK)
    return rc;
  memcpy(bc->face, face, sizeof bc->face);
  bc->nnodes = m->nnodes;
  bc->out_face = -1;
  bc->open = 0;
  bc->mask[1] = NULL;
  bc->fix = bc->mask[0] = malloc((size_t)m->nnodes);
  if (!bc->fix)
    return mpm_err_set(err, MPM_ENOMEM, "boundary mask: out of memory");
  face_mask(bc, m, bc->mask[0]);
  return MPM_OK;
}

void mpm_bc3_clear(mpm_bc3 *bc)
{
  free(bc->mask[0]);
  free(bc->mask[1]);
  free(bc->normal);
  bc->normal = NULL;
  bc->fix = bc->mask[0] = bc->mask[1] = NULL;
  bc->nnodes = 0;
  bc->out_face = -1;
  bc->open = 0;
}

/* 1 if the point s (in the outlet face's axes) lies in the outlet, boundary
 * included to tol. */
static int in_outlet(const mpm_bc3 *bc, const double s[2], double tol)
{
  if (bc->out_shape == MPM_OUTLET3_DISC) {
    const double a = s[0] - bc->out_c[0], b = s[1] - bc->out_c[1], r = bc->out_r + tol;
    return a * a + b * b <= r * r;
  }
  for (int d = 0; d < 2; d++)
    if (s[d] < bc->out_lo[d] - tol || s[d] > bc->out_hi[d] + tol)
      return 0;
  return 1;
}

/* 1 if node ijk of face f, at s in the face's axes ax, is freed when the
 * outlet opens: in it (to tol), or with held ends strictly inside it, or on a
 * rectangle's side that lies on a symmetry face (the mirror image of an
 * inner node: the orifice's centre lines in a quarter or half silo); a
 * node at a corner is freed when each of its sides is. A disc's boundary
 * is its arc: a node on a symmetry face inside the arc is strictly inside. */
static int frees_node(const mpm_bc3 *bc, const mpm_mesh3 *m, const int ijk[3], const int ax[2],
                      const double s[2], double tol, int held)
{
  if (!in_outlet(bc, s, tol))
    return 0;
  if (!held || in_outlet(bc, s, -tol))
    return 1;
  if (bc->out_shape == MPM_OUTLET3_DISC)
    return 0;
  for (int d = 0; d < 2; d++) {
    if (s[d] > bc->out_lo[d] + tol && s[d] < bc->out_hi[d] - tol)
      continue;                                          /* inside along this axis */
    const int side = 2 * ax[d] + (s[d] >= bc->out_hi[d] - tol);   /* the face at that end */
    if (!on_face(m, side, ijk) || bc->face[side] != MPM_BC_SYMMETRY)
      return 0;
  }
  return 1;
}

/* The tolerance of "on the outlet's boundary" on face f: 1e-9 of the
 * smaller unit size along it. */
static double outlet_tol(const mpm_mesh3 *m, int f)
{
  int ax[2];
  mpm_bc3_face_axes(f, ax);
  const double d[3] = {m->dx, m->dy, m->dz};
  return 1e-9 * (d[ax[0]] < d[ax[1]] ? d[ax[0]] : d[ax[1]]);
}

/* Checks, then the outlet (shape, a, b, r as stored in mpm_bc3) and the two
 * masks: the outlet's nodes closed hold the other faces' bits and the closed
 * wall's, open only the other faces'. Nothing changes on an error. */
static int set_outlet(mpm_bc3 *bc, const mpm_mesh3 *m, int f, int closed, int shape,
                      const double a[2], const double b[2], double r, int held_ends,
                      mpm_err *err)
{
  if (!bc->mask[0])
    return mpm_err_set(err, MPM_EINVAL, "outlet: boundary not set up");
  if (f < MPM_FACE_XLO || f > MPM_FACE_ZHI)
    return mpm_err_set(err, MPM_EINVAL, "outlet: unknown face %d", f);
  if (closed != MPM_BC_NOSLIP && closed != MPM_BC_FRICTIONLESS)
    return mpm_err_set(err, MPM_EINVAL, "outlet: closed kind must be noslip or frictionless");
  if (bc->face[f] == MPM_BC_PERIODIC)
    return mpm_err_set(err, MPM_EINVAL, "outlet: on a periodic face '%s'", face_names[f]);
  if (shape == MPM_OUTLET3_RECTANGLE && (!(b[0] > a[0]) || !(b[1] > a[1])))
    return mpm_err_set(err, MPM_EINVAL, "outlet: rectangle (%g, %g) x (%g, %g) m is empty",
                       a[0], b[0], a[1], b[1]);
  if (shape == MPM_OUTLET3_DISC && !(r > 0.0 && r < 1e300))
    return mpm_err_set(err, MPM_EINVAL, "outlet: disc radius %g m must be positive", r);
  unsigned char *open = malloc((size_t)bc->nnodes);
  if (!open)
    return mpm_err_set(err, MPM_ENOMEM, "outlet mask: out of memory");
  free(bc->mask[1]);
  bc->mask[1] = open;
  bc->out_face = f;
  bc->out_shape = shape;
  if (shape == MPM_OUTLET3_DISC) {
    memcpy(bc->out_c, a, sizeof bc->out_c);
    bc->out_r = r;
  } else {
    memcpy(bc->out_lo, a, sizeof bc->out_lo);
    memcpy(bc->out_hi, b, sizeof bc->out_hi);
  }
  face_mask(bc, m, bc->mask[0]);  /* a second outlet replaces the first */
  memcpy(open, bc->mask[0], (size_t)bc->nnodes);

  int ax[2];
  mpm_bc3_face_axes(f, ax);
  const double tol = outlet_tol(m, f);
  const unsigned char wall = mpm_bc_wall_bits(closed, f / 2, 3);
  int ijk[3];
  for (ijk[2] = 0; ijk[2] <= m->nz; ijk[2]++)
    for (ijk[1] = 0; ijk[1] <= m->ny; ijk[1]++)
      for (ijk[0] = 0; ijk[0] <= m->nx; ijk[0]++) {
        if (!on_face(m, f, ijk))
          continue;
        double x[3];
        mpm_mesh3_node_pos(m, ijk[0], ijk[1], ijk[2], x);
        const double s[2] = {x[ax[0]], x[ax[1]]};
        if (!frees_node(bc, m, ijk, ax, s, tol, held_ends))
          continue;                  /* held ends: the boundary's nodes keep the face's */
        const int id = mpm_mesh3_node(m, ijk[0], ijk[1], ijk[2]);
        const unsigned char others = node_bits(bc, m, ijk, f);
        open[id] = others;
        bc->mask[0][id] = (unsigned char)(others | wall);
      }
  bc->fix = bc->open ? bc->mask[1] : bc->mask[0];
  return MPM_OK;
}

int mpm_bc3_set_outlet_rectangle(mpm_bc3 *bc, const mpm_mesh3 *m, int f, const double lo[2],
                                 const double hi[2], int closed, int held_ends, mpm_err *err)
{
  return set_outlet(bc, m, f, closed, MPM_OUTLET3_RECTANGLE, lo, hi, 0.0, held_ends, err);
}

int mpm_bc3_set_outlet_disc(mpm_bc3 *bc, const mpm_mesh3 *m, int f, const double c[2],
                            double r, int closed, int held_ends, mpm_err *err)
{
  return set_outlet(bc, m, f, closed, MPM_OUTLET3_DISC, c, c, r, held_ends, err);
}

void mpm_bc3_open_outlet(mpm_bc3 *bc)
{
  if (bc->mask[1]) {
    bc->open = 1;
    bc->fix = bc->mask[1];
  }
}

int mpm_bc3_outlet_face_open(const mpm_bc3 *bc, const mpm_mesh3 *m, const int c[3])
{
  if (bc->out_face < 0)
    return 0;
  int ax[2];
  mpm_bc3_face_axes(bc->out_face, ax);
  const double o[3] = {m->x0, m->y0, m->z0}, d[3] = {m->dx, m->dy, m->dz};
  const double tol = outlet_tol(m, bc->out_face);
  for (int k = 0; k < 4; k++) {                /* the four corners of the unit's face */
    const double s[2] = {o[ax[0]] + (c[ax[0]] + (k & 1)) * d[ax[0]],
                         o[ax[1]] + (c[ax[1]] + (k >> 1)) * d[ax[1]]};
    if (!in_outlet(bc, s, tol))
      return 0;
  }
  return 1;
}

int mpm_bc3_outlet_faces(const mpm_bc3 *bc, const mpm_mesh3 *m, int lo[3], int hi[3])
{
  for (int a = 0; a < 3; a++)
    lo[a] = hi[a] = 0;
  if (bc->out_face < 0)
    return -1;
  const int f = bc->out_face;
  const int n[3] = {m->nx, m->ny, m->nz};
  int ax[2];
  mpm_bc3_face_axes(f, ax);
  int first = 1;
  for (int v = 0; v < n[ax[1]]; v++)
    for (int u = 0; u < n[ax[0]]; u++) {
      int c[3] = {0, 0, 0};
      c[ax[0]] = u;
      c[ax[1]] = v;
      if (!mpm_bc3_outlet_face_open(bc, m, c))
        continue;
      for (int k = 0; k < 2; k++) {
        const int a = ax[k];
        lo[a] = first || c[a] < lo[a] ? c[a] : lo[a];
        hi[a] = first || c[a] + 1 > hi[a] ? c[a] + 1 : hi[a];
      }
      first = 0;
    }
  if (!first) {
    lo[f / 2] = 0;                             /* across the face: every layer */
    hi[f / 2] = n[f / 2];
  }
  return f;
}

int mpm_bc3_left_through_outlet(const mpm_bc3 *bc, const mpm_mesh3 *m, const double x[3])
{
  if (!bc->open || bc->out_face < 0)
    return 0;
  const int f = bc->out_face, d = f / 2;
  const double lo[3] = {m->x0, m->y0, m->z0}, len[3] = {m->lx, m->ly, m->lz};
  if (f % 2 ? !(x[d] > lo[d] + len[d]) : !(x[d] < lo[d]))
    return 0;                                  /* not beyond the outlet's face */
  int ax[2];
  mpm_bc3_face_axes(f, ax);
  const double s[2] = {x[ax[0]], x[ax[1]]};
  return in_outlet(bc, s, 0.0);
}

int mpm_bc3_add_polygon(mpm_bc3 *bc, const mpm_mesh3 *m, int nv, const double *px,
                        const double *py, int kind, int *nheld, mpm_err *err)
{
  if (!bc->mask[0])
    return mpm_err_set(err, MPM_EINVAL, "wall: boundary not set up");
  /* the plane rule on the x-y mesh, its edges free (or periodic) */
  mpm_mesh m2;
  memset(&m2, 0, sizeof m2);
  m2.nx = m->nx;
  m2.ny = m->ny;
  m2.x0 = m->x0;
  m2.y0 = m->y0;
  m2.dx = m->dx;
  m2.dy = m->dy;
  m2.topology = MPM_TOPO_Q4;
  m2.periodic_x = m->periodic_x;
  m2.periodic_y = m->periodic_y;
  int rc = mpm_mesh_setup(&m2, err);
  if (rc != MPM_OK)
    return rc;
  const int ex = m->periodic_x ? MPM_BC_PERIODIC : MPM_BC_FREE;
  const int ey = m->periodic_y ? MPM_BC_PERIODIC : MPM_BC_FREE;
  const int edge[4] = {ex, ex, ey, ey};
  mpm_bc b2 = {0};
  int held = 0;
  if ((rc = mpm_bc_setup(&b2, &m2, edge, err)) != MPM_OK ||
      (rc = mpm_bc_add_polygon(&b2, &m2, nv, px, py, kind, NULL, err)) != MPM_OK) {
    mpm_bc_clear(&b2);
    return rc;
  }
  if (b2.normal && !bc->normal && !(bc->normal = calloc(2 * (size_t)bc->nnodes,
                                                        sizeof *bc->normal))) {
    mpm_bc_clear(&b2);
    return mpm_err_set(err, MPM_ENOMEM, "wall: no memory for node normals");
  }
  for (int j = 0; j <= m->ny; j++)
    for (int i = 0; i <= m->nx; i++) {
      const int id2 = mpm_mesh_node(&m2, i, j);
      unsigned char bits = b2.fix[id2];
      if (!bits)
        continue;
      if ((bits & (MPM_FIX_X | MPM_FIX_Y)) == (MPM_FIX_X | MPM_FIX_Y))
        bits |= MPM_FIX_Z;                       /* held whole: solid, or no-slip */
      for (int k = 0; k <= m->nz; k++) {
        const int id = mpm_mesh3_node(m, i, j, k);
        bc->mask[0][id] |= bits;
        if (bc->mask[1])
          bc->mask[1][id] |= bits;
        if (bits & MPM_FIX_N) {
          bc->normal[2 * id] = b2.normal[2 * id2];
          bc->normal[2 * id + 1] = b2.normal[2 * id2 + 1];
        }
        held += k < m->nz || !m->periodic_z;      /* an aliased layer once */
      }
    }
  mpm_bc_clear(&b2);
  if (nheld)
    *nheld = held;
  return MPM_OK;
}
