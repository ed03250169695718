/* bc3.h: boundary conditions per face of the 3D mesh of boxes (MODEL.md
 * section 2, step 3; the 3D module).
 *
 * The 3D analogue of bc.h: each of the six faces has a kind (enum
 * mpm_bc_kind in core/config.h), and they become a per-node mask of
 * constrained velocity components, MPM_FIX_X | MPM_FIX_Y | MPM_FIX_Z, by the
 * rule of the 2D edges (mpm_bc_wall_bits): no-slip holds all three,
 * frictionless and symmetry the normal one, free and periodic none. A node
 * on an edge or corner of the box takes the union of its faces' masks.
 * Periodic faces are not masks: the mesh aliases their nodes, so periodic
 * is required on both faces of an axis and exactly where the mesh is
 * periodic. An outlet is a rectangle or a disc on one face, a wall until it
 * opens; a second mask is switched in then, as in 2D. */
#ifndef MPM_BC_BC3_H
#define MPM_BC_BC3_H

#include "bc/bc.h"
#include "core/error.h"
#include "mesh/box.h"

/* Faces, in pairs along x, y, z: MPM_FACE_* / 2 is the normal's axis. */
enum { MPM_FACE_XLO = 0, MPM_FACE_XHI, MPM_FACE_YLO, MPM_FACE_YHI, MPM_FACE_ZLO, MPM_FACE_ZHI };

enum mpm_bc3_outlet_shape { MPM_OUTLET3_RECTANGLE = 0, MPM_OUTLET3_DISC };

typedef struct mpm_bc3 {
  int face[6];             /* enum mpm_bc_kind per face, MPM_FACE_* order */
  int nnodes;
  unsigned char *fix;      /* [nnodes] the mask in force (mask[0], or mask[1]
                              once the outlet is open) */
  double *normal;          /* owned, [2 nnodes]: unit normal (x, y) of the MPM_FIX_N
                              nodes of a wall prism; NULL when no side is oblique */
  unsigned char *mask[2];  /* owned: outlet closed, outlet open (NULL: no outlet) */
  int out_face;            /* MPM_FACE_* of the outlet, -1: none */
  int out_shape;           /* enum mpm_bc3_outlet_shape */
  double out_lo[2], out_hi[2];  /* rectangle: ranges along the face's axes [m] */
  double out_c[2], out_r;  /* disc: centre in the face's axes, radius [m] */
  int open;                /* 1 once mpm_bc3_open_outlet was called */
} mpm_bc3;

/* The two axes in the plane of face f, in increasing order (y, z on the x
 * faces; x, z on the y faces; x, y on the z faces): the coordinates an
 * outlet's rectangle and disc are given in. */
void mpm_bc3_face_axes(int f, int axes[2]);

/* Build the node mask for mesh m (already set up) from face[6] (MPM_FACE_*
 * order). Periodic on one face requires it on the opposite one (MPM_EINPUT)
 * and must match the mesh's periodic flags (MPM_EINVAL). */
int mpm_bc3_setup(mpm_bc3 *bc, const mpm_mesh3 *m, const int face[6], mpm_err *err);
void mpm_bc3_clear(mpm_bc3 *bc);  /* frees the masks; safe on a zeroed struct */

/* Outlet on face f: the nodes of the face whose position, in the face's axes
 * (mpm_bc3_face_axes), lies in the rectangle [lo[0], hi[0]] x [lo[1], hi[1]]
 * or in the disc of centre c and radius r (boundary included, to 1e-9 of a
 * unit) become a wall of kind `closed` (noslip or frictionless) until
 * mpm_bc3_open_outlet, and carry no condition of face f afterwards (a
 * perpendicular face meeting the outlet at an edge keeps its own, as in
 * 2D). With held_ends the nodes on the outlet's boundary (to 1e-9 of a
 * unit) keep the face's own condition and only those strictly inside are
 * freed ([DK-silo] section 7.1's orifice measured between held nodes, the
 * plane's outlet.ends = "fixed"), except on a rectangle's sides that lie on
 * a symmetry face: those are the mirror images of inner nodes (a quarter
 * silo's orifice centre lines) and are freed. The open unit faces are the
 * same either way. One outlet: a second call replaces the first. */
int mpm_bc3_set_outlet_rectangle(mpm_bc3 *bc, const mpm_mesh3 *m, int f, const double lo[2],
                                 const double hi[2], int closed, int held_ends, mpm_err *err);
int mpm_bc3_set_outlet_disc(mpm_bc3 *bc, const mpm_mesh3 *m, int f, const double c[2],
                            double r, int closed, int held_ends, mpm_err *err);
void mpm_bc3_open_outlet(mpm_bc3 *bc);

/* 1 if the face of unit c on the outlet's face has its four corners in the
 * outlet (the rule of the plane's mpm_bc_outlet_faces: an open unit face);
 * only the coordinates of c along the face are read. */
int mpm_bc3_outlet_face_open(const mpm_bc3 *bc, const mpm_mesh3 *m, const int c[3]);

/* The range of the open unit faces: units lo[a] <= c_a < hi[a] along the
 * face's two axes bound those of mpm_bc3_outlet_face_open (for a rectangle
 * they are the whole range, for a disc the ones inside it); along the
 * normal the range covers the mesh. Returns the face (MPM_FACE_*), or -1
 * with empty ranges when there is no outlet. */
int mpm_bc3_outlet_faces(const mpm_bc3 *bc, const mpm_mesh3 *m, int lo[3], int hi[3]);

/* 1 if a point at x beyond the outlet's face left through the open outlet
 * (its coordinates in the face's axes in the rectangle or disc). */
int mpm_bc3_left_through_outlet(const mpm_bc3 *bc, const mpm_mesh3 *m, const double x[3]);

/* Zero the constrained components of the vector v (momentum or force) of
 * node i (inline: the grid update applies it node by node). */
static inline void mpm_bc3_apply_node(const mpm_bc3 *bc, int i, double v[3])
{
  const unsigned char f = bc->fix[i];
  mpm_bc_apply_xy(f, bc->normal, i, &v[0], &v[1]);
  if (f & MPM_FIX_Z)
    v[2] = 0.0;
}

/* Staircase wall: the prism along z of the plane polygon (nv vertices px,
 * py), every node whose (x, y) the plane rule holds (mpm_bc_add_polygon on
 * the x-y mesh, at every z). No-slip and the solid nodes hold x, y and z; a
 * frictionless node at an open unit holds only the normal of the nearest
 * side (x, y, or MPM_FIX_N for an oblique one), so material slides along
 * the side and along z. Returns the number of nodes held in *nheld (may be
 * NULL). Call after the outlet. */
int mpm_bc3_add_polygon(mpm_bc3 *bc, const mpm_mesh3 *m, int nv, const double *px,
                        const double *py, int kind, int *nheld, mpm_err *err);

#endif
