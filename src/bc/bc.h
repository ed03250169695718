/* bc.h: boundary conditions as data (MODEL.md section 2, step 3).
 *
 * Each mesh edge has a kind (enum mpm_bc_kind in core/config.h). They become a
 * per-node mask of constrained velocity components; applying the conditions
 * zeroes those components of nodal momentum and force. Periodic edges are not
 * masks: the mesh aliases their nodes. */
#ifndef MPM_BC_BC_H
#define MPM_BC_BC_H

#include <math.h>

#include "core/config.h"
#include "core/error.h"
#include "mesh/mesh.h"

/* MPM_FIX_N: the component along the node's wall normal (an oblique
 * frictionless wall side); together with MPM_FIX_X or MPM_FIX_Y it holds both.
 * MPM_FIX_Z: the z component, in 3D (bc/bc3.h). */
enum { MPM_FIX_X = 1, MPM_FIX_Y = 2, MPM_FIX_N = 4, MPM_FIX_Z = 8 };

/* Mask bits of an axis-parallel wall of kind `kind` (enum mpm_bc_kind) whose
 * normal is along axis 0, 1 or 2 (x, y, z), in dim = 2 or 3 dimensions:
 * no-slip holds every component, frictionless and symmetry the normal one,
 * free and periodic none. The one rule for 2D edges, 2D outlets and 3D
 * faces. */
static inline unsigned char mpm_bc_wall_bits(int kind, int axis, int dim)
{
  static const unsigned char bit[3] = {MPM_FIX_X, MPM_FIX_Y, MPM_FIX_Z};
  switch (kind) {
  case MPM_BC_NOSLIP: return dim == 3 ? MPM_FIX_X | MPM_FIX_Y | MPM_FIX_Z : MPM_FIX_X | MPM_FIX_Y;
  case MPM_BC_FRICTIONLESS:
  case MPM_BC_SYMMETRY: return bit[axis];
  default: return 0;
  }
}

typedef struct mpm_bc {
  int edge[4];          /* left, right, bottom, top: enum mpm_bc_kind */
  int nnodes;
  unsigned char *fix;   /* [nnodes] MPM_FIX_X | MPM_FIX_Y | MPM_FIX_N: the mask in
                           force (mask[0], or mask[1] once the outlet is open) */
  double *normal;       /* owned, [2 nnodes]: unit normal (x, y) of the MPM_FIX_N
                           nodes; NULL when no wall side is oblique */
  unsigned char *mask[2];  /* owned: outlet closed, outlet open (NULL: no outlet) */
  int out_edge;         /* MPM_EDGE_* of the outlet, -1: none */
  double out_from, out_to;  /* its extent along the edge [m] */
  int out_held_ends;    /* 1: the nodes at out_from and out_to stay held */
  int open;             /* 1 once mpm_bc_open_outlet was called */
} mpm_bc;

enum { MPM_EDGE_LEFT = 0, MPM_EDGE_RIGHT, MPM_EDGE_BOTTOM, MPM_EDGE_TOP };

/* The acceleration handed to the points on a held (constrained) velocity
 * component of a node, boundary.wall_acceleration (docs/model.md, step 3):
 *   MPM_WALL_JUMP: the change of the nodal velocity over the step, the wall's
 *                  jump (v_wall - v_mapped)/dt included, so a point stopped
 *                  by a wall loses its velocity;
 *   MPM_WALL_ZERO: 0, [DK15] section 4 read literally (the wall fixes the
 *                  nodal momentum and suppresses its update), as [D-thesis]. */
enum mpm_bc_wall_acceleration { MPM_WALL_JUMP = 0, MPM_WALL_ZERO };

/* "jump" | "zero" <-> enum mpm_bc_wall_acceleration; -1 / NULL if unknown. */
int mpm_bc_wall_acceleration_from_name(const char *name);
const char *mpm_bc_wall_acceleration_name(int rule);

/* Name <-> enum mpm_bc_kind ("free", "noslip", "frictionless", "symmetry",
 * "periodic"); -1 if unknown. */
int mpm_bc_kind_from_name(const char *name);
const char *mpm_bc_kind_name(int kind);

/* Build the node mask for mesh m (already set up, periodic flags consistent
 * with the edges). Periodic on one edge requires periodic on its opposite. */
int mpm_bc_setup(mpm_bc *bc, const mpm_mesh *m, const int edge[4], mpm_err *err);
void mpm_bc_clear(mpm_bc *bc);  /* frees the mask; safe on a zeroed struct */

/* Zero constrained components of nodal vectors ax, ay (momentum or force):
 * x and y, or the normal one, (ax, ay) -= ((ax, ay) . n) n. */
void mpm_bc_apply(const mpm_bc *bc, double *ax, double *ay);

/* The x-y part of mask f of node i on (*ax, *ay): x and y held, or the
 * component along the node's unit wall normal (normal[2i], normal[2i+1]),
 * (ax, ay) -= ((ax, ay) . n) n; with x or y held as well, both. The plane
 * and the 3D nodes (whose walls are prisms along z) share it. */
static inline void mpm_bc_apply_xy(unsigned char f, const double *normal, int i, double *ax,
                                   double *ay)
{
  if ((f & MPM_FIX_N) && (f & (MPM_FIX_X | MPM_FIX_Y)))
    f = MPM_FIX_X | MPM_FIX_Y;                    /* two independent normals */
  if (f & MPM_FIX_N) {
    const double nx = normal[2 * i], ny = normal[2 * i + 1];
    const double an = *ax * nx + *ay * ny;
    *ax -= an * nx;
    *ay -= an * ny;
  }
  if (f & MPM_FIX_X)
    *ax = 0.0;
  if (f & MPM_FIX_Y)
    *ay = 0.0;
}

/* The same for the vector (*ax, *ay) of node i alone (inline: the grid
 * update applies it node by node). */
static inline void mpm_bc_apply_node(const mpm_bc *bc, int i, double *ax, double *ay)
{
  mpm_bc_apply_xy(bc->fix[i], bc->normal, i, ax, ay);
}

/* 1 if (x, y) lies outside the mesh's closed rectangle (a point there may
 * need mpm_bc_clamp; inside it never does). */
static inline int mpm_bc_outside(const mpm_mesh *m, double x, double y)
{
  return (x < m->x0) | (x > m->x0 + m->lx) | (y < m->y0) | (y > m->y0 + m->ly);
}

/* 1 if an edge or face of this kind is a wall that material cannot cross. */
static inline int mpm_bc_is_wall(int kind)
{
  return kind == MPM_BC_NOSLIP || kind == MPM_BC_FRICTIONLESS || kind == MPM_BC_SYMMETRY;
}

/* Along one axis of a mesh [lo, hi]: a point beyond a wall end (wall_lo,
 * wall_hi) is put back on it, and its velocity v into that wall limited to
 * the grid's gv (none if the grid moves away). */
static inline void mpm_bc_clamp_axis(double *x, double *v, double gv, double lo, double hi,
                                     int wall_lo, int wall_hi)
{
  if (*x < lo && wall_lo) {
    *x = lo;
    *v = fmax(*v, fmin(gv, 0.0));
  }
  if (*x > hi && wall_hi) {
    *x = hi;
    *v = fmin(*v, fmax(gv, 0.0));
  }
}

/* Move a point that crossed a wall edge (no-slip, frictionless, symmetry)
 * back onto it, and let its velocity (vx, vy) point into that wall no faster
 * than the grid velocity (gvx, gvy) that carried it there. Positions are
 * advanced with interpolated grid velocity, which near a wall can carry a
 * point a fraction of a step past it (next to an open outlet, where the
 * nearest node is free, every step); FLIP would otherwise keep adding the
 * free node's acceleration to a point that stands still, without bound.
 * Free edges are left alone (leaving through them is an error for the
 * caller). */
void mpm_bc_clamp(const mpm_bc *bc, const mpm_mesh *m, double *x, double *y, double *vx,
                  double *vy, double gvx, double gvy);

/* Outlet: the nodes of edge e (MPM_EDGE_*) whose coordinate along the edge
 * lies in [from, to] (ends included; with held_ends, strictly inside) become
 * a wall of kind `closed` (noslip or frictionless) until mpm_bc_open_outlet,
 * and carry no condition of that edge afterwards (a perpendicular edge
 * meeting the outlet at a corner, such as a symmetry line, keeps its own);
 * with held_ends the nodes at from and to keep the edge's own condition,
 * unless that end is a corner on a symmetry line (a half silo's centre: the
 * mirror image of an inner node), which is freed.
 * The orifice size to - from is then the distance between the first and
 * last free node ([DK15] section 4.2) or between the held nodes that bound
 * it ([DK-silo] section 7.1). Its unit faces (mpm_bc_outlet_faces) are those
 * within [from, to] either way. Call after mpm_bc_setup, before
 * mpm_bc_add_polygon. */
int mpm_bc_set_outlet(mpm_bc *bc, const mpm_mesh *m, int e, double from, double to,
                      int closed, int held_ends, mpm_err *err);
void mpm_bc_open_outlet(mpm_bc *bc);

/* Staircase wall: every node inside or on the polygon (nv vertices, within
 * 1e-9 of a unit of its boundary) is held. Noslip: both components. Frictionless:
 * a held node that is a corner of an open unit (centre outside the polygon or
 * on a side) holds only the component along the normal of the nearest side,
 * x or y for an axis-parallel side, MPM_FIX_N for an oblique one, so material
 * slides along the side as along a smooth wall; the other held nodes hold
 * both. Returns the number of nodes held in *nheld (may be NULL). */
int mpm_bc_add_polygon(mpm_bc *bc, const mpm_mesh *m, int nv, const double *px,
                       const double *py, int kind, int *nheld, mpm_err *err);

/* The unit faces of the outlet: faces lo .. hi-1 along its edge (unit
 * columns on the bottom and top, rows on the left and right) have both end
 * nodes in the outlet. Returns the edge (MPM_EDGE_*), or -1 with lo = hi = 0
 * when there is no outlet. */
int mpm_bc_outlet_faces(const mpm_bc *bc, const mpm_mesh *m, int *lo, int *hi);

/* 1 if a point at (x, y) outside the mesh left through an open outlet. */
int mpm_bc_left_through_outlet(const mpm_bc *bc, const mpm_mesh *m, double x, double y);

#endif
