/* box.h: structured 3D background mesh of boxes, "hexahedral units", with the
 * trilinear (Q8) basis, for the 3D module (MODEL.md sections 3 and 7).
 *
 * nx x ny x nz units of size dx x dy x dz from (x0, y0, z0). Periodic axes
 * alias node i = nx with i = 0 (likewise j, k), as in 2D: aliased nodes share
 * one storage index, id = (k_s sny + j_s) snx + i_s, so every nodal array has
 * nnodes entries. Locating a point is the 2D per-axis code
 * (mpm_mesh_axis_locate) once per axis.
 *
 * A struct of its own, not fields added to mpm_mesh: the 2D step copies its
 * mesh into registers and branches on its topology in the hot loops; a z
 * axis there would grow the copy and add tests to every 2D point for
 * nothing. Sharing happens per axis instead (mpm_mesh_axis_*, and the axis
 * checks of mesh_internal.h), so 2D code and its speed stay as they were.
 *
 * The corners of a unit are numbered as a VTK/XDMF hexahedron: the bottom
 * face (w = 0) in the Q4 order (i, j), (i+1, j), (i+1, j+1), (i, j+1), then
 * the top face (w = 1) in the same order. */
#ifndef MPM_MESH_BOX_H
#define MPM_MESH_BOX_H

#include "core/config.h"
#include "core/error.h"
#include "mesh/mesh.h"

typedef struct mpm_mesh3 {
  /* set by the caller before mpm_mesh3_setup */
  int nx, ny, nz;                  /* units */
  double x0, y0, z0, dx, dy, dz;   /* origin and unit size [m] */
  int periodic_x, periodic_y, periodic_z;
  /* derived by mpm_mesh3_setup */
  int snx, sny, snz;               /* stored nodes along each axis (n or n + 1) */
  int nnodes;                      /* snx sny snz */
  double lx, ly, lz;               /* domain size n d */
  double idx, idy, idz;            /* 1/dx, 1/dy, 1/dz */
} mpm_mesh3;

/* Validate the caller's fields and fill the derived ones (MPM_EINPUT names
 * the field, as mpm_mesh_setup does). */
int mpm_mesh3_setup(mpm_mesh3 *m, mpm_err *err);

/* The box mesh of a 3D input (mesh.nz > 0): units and origin of the mesh
 * section, periodic axes where boundary.left, .bottom, .front are
 * "periodic"; set up (errors as mpm_mesh3_setup; err may be NULL). */
int mpm_mesh3_from_config(mpm_mesh3 *m, const mpm_config *cfg, mpm_err *err);

/* Storage index of logical node (i, j, k), with periodic aliasing (any
 * integer index along a periodic axis). */
int mpm_mesh3_node(const mpm_mesh3 *m, int i, int j, int k);

/* Position of logical node (i, j, k). */
void mpm_mesh3_node_pos(const mpm_mesh3 *m, int i, int j, int k, double x[3]);

/* Unit (i, j, k) = u[0..2] of x (after wrapping along periodic axes) and the
 * local coordinates (u, v, w) = l[0..2] in [0, 1]^3 of the point in it; a
 * point on an upper face belongs to the last unit. 0, or -1 outside a
 * non-periodic face (or not finite). */
static inline int mpm_mesh3_locate(const mpm_mesh3 *m, const double x[3], int u[3],
                                   double l[3])
{
  return mpm_mesh_axis_locate(x[0], m->x0, m->lx, m->idx, m->nx, m->periodic_x, &u[0], &l[0]) ||
         mpm_mesh_axis_locate(x[1], m->y0, m->ly, m->idy, m->ny, m->periodic_y, &u[1], &l[1]) ||
         mpm_mesh_axis_locate(x[2], m->z0, m->lz, m->idz, m->nz, m->periodic_z, &u[2], &l[2])
           ? -1 : 0;
}

/* Storage ids of the 8 corners of unit (i, j, k) (0 <= i < nx, ...) in the
 * hexahedron order (header), with periodic aliasing. */
static inline void mpm_mesh3_unit_corners(const mpm_mesh3 *m, int i, int j, int k, int c[8])
{
  const int sxy = m->snx * m->sny;
  int dx = 1, dy = m->snx, dz = sxy;               /* the next column, row, layer */
  if (m->periodic_x && i + 1 == m->nx)
    dx = 1 - m->nx;                                /* node nx aliases node 0 */
  if (m->periodic_y && j + 1 == m->ny)
    dy = (1 - m->ny) * m->snx;
  if (m->periodic_z && k + 1 == m->nz)
    dz = (1 - m->nz) * sxy;
  const int n0 = (k * m->sny + j) * m->snx + i;
  c[0] = n0;
  c[1] = n0 + dx;
  c[2] = n0 + dx + dy;
  c[3] = n0 + dy;
  for (int a = 0; a < 4; a++)
    c[4 + a] = c[a] + dz;
}

/* Trilinear (Q8) values at local (u, v, w) on the unit corners (hexahedron
 * order): N = f g h with f = 1-u, u, u, 1-u, g = 1-v, 1-v, v, v on both
 * faces and h = 1-w on the bottom face, w on the top one. */
static inline void mpm_mesh3_shape_q8(double u, double v, double w, double N[8])
{
  const double f[4] = {1.0 - u, u, u, 1.0 - u}, g[4] = {1.0 - v, 1.0 - v, v, v};
  for (int a = 0; a < 4; a++) {
    N[a] = f[a] * g[a] * (1.0 - w);
    N[4 + a] = f[a] * g[a] * w;
  }
}

/* Trilinear (Q8) basis at local (u, v, w) on the unit corners (hexahedron
 * order), with 1/dx = ix, 1/dy = iy, 1/dz = iz: per corner a,
 * N_a = f_a g_a h_a with f = 1-u or u, g = 1-v or v, h = 1-w or w, and
 * grad N_a = (su_a g_a h_a / dx, sv_a f_a h_a / dy, sw_a f_a g_a / dz)
 * (su, sv, sw the signs: -1 where the factor is 1-u, ...). */
static inline void mpm_mesh3_basis_q8(double u, double v, double w, double ix, double iy,
                                      double iz, double N[8], double dNx[8], double dNy[8],
                                      double dNz[8])
{
  const double su[8] = {-1, 1, 1, -1, -1, 1, 1, -1}, cu[8] = {1, 0, 0, 1, 1, 0, 0, 1};
  const double sv[8] = {-1, -1, 1, 1, -1, -1, 1, 1}, cv[8] = {1, 1, 0, 0, 1, 1, 0, 0};
  const double sw[8] = {-1, -1, -1, -1, 1, 1, 1, 1}, cw[8] = {1, 1, 1, 1, 0, 0, 0, 0};
#pragma omp simd
  for (int a = 0; a < 8; a++) {
    const double f = cu[a] + su[a] * u, g = cv[a] + sv[a] * v, h = cw[a] + sw[a] * w;
    N[a] = f * g * h;
    dNx[a] = su[a] * g * h * ix;
    dNy[a] = sv[a] * f * h * iy;
    dNz[a] = sw[a] * f * g * iz;
  }
}

/* The basis of a located point (unit u[0..2], local l[0..2]) on the unit's
 * corners: storage ids, N, grad N; returns 8. */
static inline int mpm_mesh3_basis_at(const mpm_mesh3 *m, const int u[3], const double l[3],
                                     int node[8], double N[8], double dNx[8], double dNy[8],
                                     double dNz[8])
{
  mpm_mesh3_unit_corners(m, u[0], u[1], u[2], node);
  mpm_mesh3_basis_q8(l[0], l[1], l[2], m->idx, m->idy, m->idz, N, dNx, dNy, dNz);
  return 8;
}

/* The basis at x: mpm_mesh3_locate then mpm_mesh3_basis_at; returns 8, or
 * -1 when x is outside a non-periodic face. */
int mpm_mesh3_basis(const mpm_mesh3 *m, const double x[3], int node[8], double N[8],
                    double dNx[8], double dNy[8], double dNz[8]);

#endif
