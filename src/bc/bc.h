/* bc.h: boundary conditions as data (MODEL.md section 2, step 3), for a
 * mesh of either dimension.
 *
 * Each face of the mesh (the plane's four edges, a box's six faces) has a
 * kind (enum mpm_bc_kind in core/config.h). They become a per-node mask of
 * constrained velocity components: no-slip holds every component,
 * frictionless and symmetry the normal one, free and periodic none; a node
 * on an edge or corner of the domain takes the union of its faces' masks.
 * Applying the conditions zeroes those components of nodal momentum and
 * force. Periodic faces are not masks: the mesh aliases their nodes, so
 * periodic is required on both faces of an axis and exactly where the mesh
 * is periodic. An outlet (walls.c) is a stretch of one face, a (D-1)-box
 * (the plane's interval of an edge, a rectangle of a box's face) or a disc
 * (3D), that is a wall until it opens: a second mask is switched in then.
 * Staircase walls (walls.c) are the nodes inside a plane polygon, in 3D the
 * prism along z of it.
 *
 * These walls are fixed. Walls that move are rigid bodies (body.h), which
 * correct the nodes near them after the grid update and keep what a mask
 * holds held (docs/design.md, "Moving bodies"). */
#ifndef MPM_BC_BC_H
#define MPM_BC_BC_H

#include <math.h>

#include "core/config.h"
#include "core/error.h"
#include "mesh/mesh.h"

/* MPM_FIX_N: the component along the node's wall normal (an oblique
 * frictionless wall side, in the x-y plane); together with MPM_FIX_X or
 * MPM_FIX_Y it holds both. MPM_FIX_Z: the z component, in 3D. */
enum { MPM_FIX_X = 1, MPM_FIX_Y = 2, MPM_FIX_N = 4, MPM_FIX_Z = 8 };

/* Faces, in pairs along x, y, z: MPM_FACE_* / 2 is the normal's axis, % 2
 * the end (0 the lower). The plane's edges left, right, bottom, top are
 * faces 0 .. 3. */
enum { MPM_FACE_XLO = 0, MPM_FACE_XHI, MPM_FACE_YLO, MPM_FACE_YHI, MPM_FACE_ZLO, MPM_FACE_ZHI };

/* Mask bits of an axis-parallel wall of kind `kind` (enum mpm_bc_kind) whose
 * normal is along axis 0, 1 or 2 (x, y, z), in dim = 2 or 3 dimensions:
 * no-slip holds every component, frictionless and symmetry the normal one,
 * free and periodic none. The one rule for faces and outlets. */
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

/* The shape of an outlet on its face. */
enum mpm_bc_outlet_shape { MPM_BC_OUTLET_BOX = 0, MPM_BC_OUTLET_DISC };

typedef struct mpm_bc {
  int dim;                 /* of the mesh: 2 or 3 faces pairs */
  int face[6];             /* enum mpm_bc_kind per face, MPM_FACE_* order */
  int nnodes;
  unsigned char *fix;      /* [nnodes] the mask in force (mask[0], or mask[1] once
                              the outlet is open) */
  double *normal;          /* owned, [2 nnodes]: unit normal (x, y) of the MPM_FIX_N
                              nodes of a wall; NULL when no wall side is oblique */
  unsigned char *mask[2];  /* owned: outlet closed, outlet open (NULL: no outlet) */
  int out_face;            /* MPM_FACE_* of the outlet, -1: none */
  int out_shape;           /* enum mpm_bc_outlet_shape */
  double out_lo[2], out_hi[2];  /* box: ranges along the face's axes [m] */
  double out_c[2], out_r;  /* disc: centre in the face's axes, radius [m] */
  int out_held;            /* 1: the nodes on the outlet's boundary stay held */
  int open;                /* 1 once mpm_bc_open_outlet was called */
} mpm_bc;

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

/* Build the node mask for mesh m (already set up) from the kinds of its
 * 2 dim faces face[] (MPM_FACE_* order). Periodic on one face requires it
 * on the opposite one (MPM_EINPUT) and must match the mesh's periodic axes
 * (MPM_EINVAL). */
int mpm_bc_setup(mpm_bc *bc, const mpm_mesh *m, const int face[], mpm_err *err);
void mpm_bc_clear(mpm_bc *bc);  /* frees the masks; safe on a zeroed struct */

/* The x-y part of mask f of node i on (*ax, *ay): x and y held, or the
 * component along the node's unit wall normal (normal[2i], normal[2i+1]),
 * (ax, ay) -= ((ax, ay) . n) n; with x or y held as well, both. */
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

/* Zero the constrained components of the vector v[D] (momentum or force) of
 * node i, D the mesh's dimension (inline: the grid update applies it node
 * by node). */
static inline void mpm_bc_apply_node(const mpm_bc *bc, int i, int D, double *v)
{
  const unsigned char f = bc->fix[i];
  mpm_bc_apply_xy(f, bc->normal, i, &v[0], &v[1]);
  if (D == 3 && (f & MPM_FIX_Z))
    v[2] = 0.0;
}

/* 1 if an edge or face of this kind is a wall that material cannot cross. */
static inline int mpm_bc_is_wall(int kind)
{
  return kind == MPM_BC_NOSLIP || kind == MPM_BC_FRICTIONLESS || kind == MPM_BC_SYMMETRY;
}

/* Along one axis of a mesh [lo, hi]: a point beyond a wall end (wall_lo,
 * wall_hi) is put back on it, and its velocity v into that wall limited to
 * the grid's gv (none if the grid moves away). Positions are advanced with
 * interpolated grid velocity, which near a wall can carry a point a
 * fraction of a step past it (next to an open outlet, where the nearest
 * node is free, every step); FLIP would otherwise keep adding the free
 * node's acceleration to a point that stands still, without bound. */
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

/* ---- outlets and staircase walls (walls.c) ---------------------------------- */

/* The D-1 axes in the plane of face f of a mesh of dimension dim, in
 * increasing order (plane: y on the x edges, x on the y edges; 3D: y, z on
 * the x faces, x, z on the y faces, x, y on the z faces): the coordinates
 * an outlet is given in. Returns their number. */
int mpm_bc_face_axes(int dim, int f, int axes[2]);

/* Outlet on face f: the nodes of the face whose position, in the face's axes
 * (mpm_bc_face_axes), lies in the box [lo[0], hi[0]] (x [lo[1], hi[1]]) or
 * (3D) in the disc inscribed in it, of centre (lo + hi)/2 and radius
 * (hi[0] - lo[0])/2 (boundary included, to 1e-9 of a unit) become a wall of kind `closed` (noslip or
 * frictionless) until mpm_bc_open_outlet, and carry no condition of face f
 * afterwards (a perpendicular face meeting the outlet at an edge or corner,
 * such as a symmetry plane, keeps its own). With held_ends the nodes on the
 * outlet's boundary (to 1e-9 of a unit) keep the face's own condition and
 * only those strictly inside are freed ([DK-silo] section 7.1's orifice
 * measured between held nodes; without, [DK15] section 4.2's between the
 * first and last free node), except on a box's sides that lie on a symmetry
 * face: those are the mirror images of inner nodes (a half or quarter
 * silo's orifice centre) and are freed. The open unit faces are the same
 * either way. One outlet: a second call replaces the first. Call after
 * mpm_bc_setup, before mpm_bc_add_polygon. */
int mpm_bc_set_outlet(mpm_bc *bc, const mpm_mesh *m, int f, int shape, const double lo[2],
                      const double hi[2], int closed, int held_ends, mpm_err *err);
void mpm_bc_open_outlet(mpm_bc *bc);

/* 1 if the face of unit c on the outlet's face has all its corners in the
 * outlet: an open unit face; only the coordinates of c along the face are
 * read. */
int mpm_bc_outlet_face_open(const mpm_bc *bc, const mpm_mesh *m, const int c[3]);

/* The range of the open unit faces: units lo[a] <= c_a < hi[a] along the
 * face's axes bound those of mpm_bc_outlet_face_open (for a box they are the
 * whole range, for a disc the ones inside it); along the normal (and the
 * plane's z) the range covers the mesh. Returns the face (MPM_FACE_*), or -1
 * with empty ranges when there is no outlet. */
int mpm_bc_outlet_faces(const mpm_bc *bc, const mpm_mesh *m, int lo[3], int hi[3]);

/* 1 if a point at x beyond the outlet's face left through the open outlet
 * (its coordinates along the face in the box or disc). */
int mpm_bc_left_through_outlet(const mpm_bc *bc, const mpm_mesh *m, const double x[3]);

/* Staircase wall: every node inside or on the plane polygon (nv vertices px,
 * py; within 1e-9 of a unit of its boundary), at every z in 3D (the prism),
 * is held. Noslip, and the nodes inside: every component. Frictionless: a
 * held node that is a corner of an open unit (centre outside the polygon or
 * on a side) holds only the component along the normal of the nearest side
 * (x or y for an axis-parallel side, MPM_FIX_N for an oblique one), so
 * material slides along the side (and along z). Returns the number of nodes
 * held in *nheld (may be NULL). Call after the outlet. */
int mpm_bc_add_polygon(mpm_bc *bc, const mpm_mesh *m, int nv, const double *px,
                       const double *py, int kind, int *nheld, mpm_err *err);

#endif
