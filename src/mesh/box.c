/* box.c: structured 3D background mesh of boxes (box.h; MODEL.md sections 3
 * and 7).
 *
 * Validation with the 2D mesh's per-axis checks (mesh_internal.h), node
 * numbering with periodic aliasing, id = (k_s sny + j_s) snx + i_s with
 * i_s = i mod nx along a periodic x (likewise j, k), and the trilinear basis
 * at a position. */
#include "mesh/box.h"

#include <limits.h>

#include "mesh/mesh_internal.h"

int mpm_mesh3_setup(mpm_mesh3 *m, mpm_err *err)
{
  int rc;
  if ((rc = mpm_mesh_in_check_units(m->nx, m->periodic_x, 2, 'x', err)) != MPM_OK ||
      (rc = mpm_mesh_in_check_units(m->ny, m->periodic_y, 2, 'y', err)) != MPM_OK ||
      (rc = mpm_mesh_in_check_units(m->nz, m->periodic_z, 2, 'z', err)) != MPM_OK ||
      (rc = mpm_mesh_in_check_lengths(m->nx, m->x0, m->dx, 'x', err)) != MPM_OK ||
      (rc = mpm_mesh_in_check_lengths(m->ny, m->y0, m->dy, 'y', err)) != MPM_OK ||
      (rc = mpm_mesh_in_check_lengths(m->nz, m->z0, m->dz, 'z', err)) != MPM_OK)
    return rc;
  const int snx = m->periodic_x ? m->nx : m->nx + 1;
  const int sny = m->periodic_y ? m->ny : m->ny + 1;
  const int snz = m->periodic_z ? m->nz : m->nz + 1;
  const long long sxy = (long long)snx * sny;      /* < 2^62: no overflow */
  const long long nn = sxy <= INT_MAX ? sxy * snz : sxy;
  if (sxy > INT_MAX || nn > INT_MAX)
    return mpm_err_set(err, MPM_EINPUT,
                       "mesh.nx = %d, mesh.ny = %d, mesh.nz = %d: too many nodes "
                       "(allowed: at most %d)", m->nx, m->ny, m->nz, INT_MAX);
  m->snx = snx;
  m->sny = sny;
  m->snz = snz;
  m->nnodes = (int)nn;
  m->lx = m->nx * m->dx;
  m->ly = m->ny * m->dy;
  m->lz = m->nz * m->dz;
  m->idx = 1.0 / m->dx;
  m->idy = 1.0 / m->dy;
  m->idz = 1.0 / m->dz;
  return MPM_OK;
}

int mpm_mesh3_node(const mpm_mesh3 *m, int i, int j, int k)
{
  const int is = mpm_mesh_in_axis_store(i, m->nx, m->periodic_x);
  const int js = mpm_mesh_in_axis_store(j, m->ny, m->periodic_y);
  const int ks = mpm_mesh_in_axis_store(k, m->nz, m->periodic_z);
  return (ks * m->sny + js) * m->snx + is;  /* id = (k_s sny + j_s) snx + i_s */
}

void mpm_mesh3_node_pos(const mpm_mesh3 *m, int i, int j, int k, double x[3])
{
  x[0] = m->x0 + i * m->dx;
  x[1] = m->y0 + j * m->dy;
  x[2] = m->z0 + k * m->dz;
}

int mpm_mesh3_basis(const mpm_mesh3 *m, const double x[3], int node[8], double N[8],
                    double dNx[8], double dNy[8], double dNz[8])
{
  int u[3];
  double l[3];
  if (mpm_mesh3_locate(m, x, u, l))
    return -1;
  return mpm_mesh3_basis_at(m, u, l, node, N, dNx, dNy, dNz);
}

int mpm_mesh3_from_config(mpm_mesh3 *m, const mpm_config *cfg, mpm_err *err)
{
  *m = (mpm_mesh3){.nx = cfg->mesh.nx, .ny = cfg->mesh.ny, .nz = cfg->mesh.nz,
                   .x0 = cfg->mesh.x0, .y0 = cfg->mesh.y0, .z0 = cfg->mesh.z0,
                   .dx = cfg->mesh.dx, .dy = cfg->mesh.dy, .dz = cfg->mesh.dz,
                   .periodic_x = cfg->bc.left == MPM_BC_PERIODIC,
                   .periodic_y = cfg->bc.bottom == MPM_BC_PERIODIC,
                   .periodic_z = cfg->bc.front == MPM_BC_PERIODIC};
  return mpm_mesh3_setup(m, err);
}
