/* mesh.h: structured 2D background mesh (MODEL.md section 3).
 *
 * nx x ny square-ish "units" of size dx x dy from (x0, y0). Topology Q4
 * (bilinear unit) or T3 (each unit split into two linear triangles along a
 * diagonal chosen per unit: "/" bottom-left to top-right, "\" the other, or
 * "mirror": "/" left of x = mirror_x and "\" right of it, [DK-silo] 7.1).
 * Periodic directions alias node i = nx with i = 0 (likewise j): aliased nodes
 * share one storage index, so every nodal array has mesh.nnodes entries. */
#ifndef MPM_MESH_MESH_H
#define MPM_MESH_MESH_H

#include <stddef.h>

#include "core/config.h"
#include "core/error.h"

enum mpm_topology { MPM_TOPO_Q4 = 0, MPM_TOPO_T3 };
enum mpm_diagonal { MPM_DIAG_SLASH = 0, MPM_DIAG_BACKSLASH, MPM_DIAG_MIRROR };

typedef struct mpm_mesh {
  /* set by the caller before mpm_mesh_setup */
  int nx, ny;            /* units */
  double x0, y0, dx, dy; /* origin and unit size [m] */
  int topology;          /* enum mpm_topology */
  int diagonal;          /* enum mpm_diagonal (T3 only) */
  double mirror_x;       /* mirror line for MPM_DIAG_MIRROR [m] */
  int periodic_x, periodic_y;
  /* derived by mpm_mesh_setup */
  int snx, sny;          /* stored nodes per row / column (nx or nx+1) */
  int nnodes;            /* snx * sny */
  double lx, ly;         /* domain size nx*dx, ny*dy */
  double idx, idy;       /* 1/dx, 1/dy (kept for the hot loops) */
} mpm_mesh;

/* Validate the caller's fields and fill the derived ones. */
int mpm_mesh_setup(mpm_mesh *m, mpm_err *err);

/* Name <-> enum ("q4", "t3"; "/", "\\", "mirror"): -1 / NULL if unknown. */
int mpm_mesh_topology_from_name(const char *name);
const char *mpm_mesh_topology_name(int topology);
int mpm_mesh_diagonal_from_name(const char *name);
const char *mpm_mesh_diagonal_name(int diagonal);

/* The mesh of a resolved input (mesh section, periodic from the bc section),
 * set up; MPM_EINPUT names an unknown topology or diagonal. */
int mpm_mesh_from_config(mpm_mesh *m, const mpm_config *cfg, mpm_err *err);

/* Storage index of logical node (i, j), 0 <= i <= nx, 0 <= j <= ny, with
 * periodic aliasing. */
int mpm_mesh_node(const mpm_mesh *m, int i, int j);

/* Position of logical node (i, j). */
void mpm_mesh_node_pos(const mpm_mesh *m, int i, int j, double *x, double *y);

/* Wrap a position into the domain along periodic directions. */
void mpm_mesh_wrap(const mpm_mesh *m, double *x, double *y);

/* Unit (i, j) containing (x, y) (after wrapping); a point on the upper or right
 * boundary belongs to the last unit. Returns MPM_OK or MPM_EOUTSIDE. */
int mpm_mesh_unit(const mpm_mesh *m, double x, double y, int *i, int *j);

/* 1 if the T3 unit (i, j) is cut along "/", 0 if along "\". */
int mpm_mesh_unit_is_slash(const mpm_mesh *m, int i, int j);

/* Linear (T3) or bilinear (Q4) basis of the element containing (x, y):
 * writes the storage ids of its nodes, N and grad N; returns the node count
 * (3 or 4), or -1 when (x, y) is outside a non-periodic direction. */
int mpm_mesh_basis(const mpm_mesh *m, double x, double y,
                   int node[4], double N[4], double dNx[4], double dNy[4]);

#endif
