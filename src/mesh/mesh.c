/* mesh.c: structured 2D background mesh (MODEL.md section 3).
 *
 * Validation of the caller's fields, node numbering with periodic aliasing
 * (storage id = j_s * snx + i_s, i_s = i mod nx along a periodic x), unit
 * lookup, and the element basis: bilinear Q4, or linear T3 on the half of the
 * unit cut by its diagonal ("/", "\", or "mirror" about x = mirror_x,
 * [DK-silo] 7.1). The basis is in the hot loop: no allocation, no division. */
#include "mesh/mesh.h"

#include <limits.h>
#include <math.h>
#include <string.h>

#include "core/names.h"
#include "mesh/mesh_internal.h"

/* ---------------------------------------------------------------- setup */

/* Units along one axis: n >= 1, periodic flag 0/1, n >= nper when periodic. */
int mpm_mesh_in_check_units(int n, int periodic, int nper, char axis, mpm_err *err)
{
  if (periodic != 0 && periodic != 1)
    return mpm_err_set(err, MPM_EINPUT,
                       "mesh.periodic_%c = %d is out of range (allowed: 0 or 1)",
                       axis, periodic);
  if (n < 1 || n > INT_MAX - 1)
    return mpm_err_set(err, MPM_EINPUT,
                       "mesh.n%c = %d is out of range (allowed: integer >= 1)",
                       axis, n);
  if (periodic && n < nper)
    return mpm_err_set(err, MPM_EINPUT,
                       "mesh.n%c = %d is out of range (allowed: n%c >= %d when %c "
                       "is periodic)", axis, n, axis, nper, axis);
  return MPM_OK;
}

/* Origin finite, unit size finite and > 0, domain end finite. */
int mpm_mesh_in_check_lengths(int n, double o, double h, char axis, mpm_err *err)
{
  if (!isfinite(o))
    return mpm_err_set(err, MPM_EINPUT,
                       "mesh.%c0 = %g is out of range (allowed: finite) [m]",
                       axis, o);
  if (!(h > 0.0) || !isfinite(h))
    return mpm_err_set(err, MPM_EINPUT,
                       "mesh.d%c = %g is out of range (allowed: finite, > 0) [m]",
                       axis, h);
  if (!isfinite(o + n * h))
    return mpm_err_set(err, MPM_EINPUT,
                       "mesh.%c0 + mesh.n%c * mesh.d%c = %g is not finite [m]",
                       axis, axis, axis, o + n * h);
  return MPM_OK;
}

/* Topology, diagonal rule, mirror line. */
static int check_topology(const mpm_mesh *m, mpm_err *err)
{
  if (m->topology != MPM_TOPO_Q4 && m->topology != MPM_TOPO_T3)
    return mpm_err_set(err, MPM_EINPUT,
                       "mesh.topology = %d is out of range (allowed: %d = q4, "
                       "%d = t3)", m->topology, MPM_TOPO_Q4, MPM_TOPO_T3);
  if (m->diagonal < MPM_DIAG_SLASH || m->diagonal > MPM_DIAG_MIRROR)
    return mpm_err_set(err, MPM_EINPUT,
                       "mesh.diagonal = %d is out of range (allowed: %d = \"/\", "
                       "%d = \"\\\", %d = \"mirror\")", m->diagonal,
                       MPM_DIAG_SLASH, MPM_DIAG_BACKSLASH, MPM_DIAG_MIRROR);
  if (m->topology == MPM_TOPO_T3 && m->diagonal == MPM_DIAG_MIRROR &&
      !isfinite(m->mirror_x))
    return mpm_err_set(err, MPM_EINPUT,
                       "mesh.mirror_x = %g is out of range (allowed: finite) [m]",
                       m->mirror_x);
  return MPM_OK;
}

int mpm_mesh_setup(mpm_mesh *m, mpm_err *err)
{
  int rc;
  /* a periodic axis of one unit is one node row or column: its two edges
   * are one node, so nothing varies along it (the infinite layer of [DK15]
   * section 4.4 and [DK-silo] section 6 on one column of elements) */
  if ((rc = mpm_mesh_in_check_units(m->nx, m->periodic_x, 1, 'x', err)) != MPM_OK ||
      (rc = mpm_mesh_in_check_units(m->ny, m->periodic_y, 1, 'y', err)) != MPM_OK ||
      (rc = mpm_mesh_in_check_lengths(m->nx, m->x0, m->dx, 'x', err)) != MPM_OK ||
      (rc = mpm_mesh_in_check_lengths(m->ny, m->y0, m->dy, 'y', err)) != MPM_OK ||
      (rc = check_topology(m, err)) != MPM_OK)
    return rc;
  int snx = m->periodic_x ? m->nx : m->nx + 1;
  int sny = m->periodic_y ? m->ny : m->ny + 1;
  if ((long long)snx * sny > INT_MAX)
    return mpm_err_set(err, MPM_EINPUT,
                       "mesh.nx = %d, mesh.ny = %d: %lld nodes is out of range "
                       "(allowed: at most %d)", m->nx, m->ny,
                       (long long)snx * sny, INT_MAX);
  m->snx = snx;
  m->sny = sny;
  m->nnodes = snx * sny;
  m->lx = m->nx * m->dx;
  m->ly = m->ny * m->dy;
  m->idx = 1.0 / m->dx;
  m->idy = 1.0 / m->dy;
  return MPM_OK;
}

/* ---------------------------------------------------------------- names */

static const char *const topology_names[] = {[MPM_TOPO_Q4] = "q4", [MPM_TOPO_T3] = "t3"};
static const char *const diagonal_names[] = {
  [MPM_DIAG_SLASH] = "/", [MPM_DIAG_BACKSLASH] = "\\", [MPM_DIAG_MIRROR] = "mirror"
};

int mpm_mesh_topology_from_name(const char *name)
{
  return mpm_names_index(topology_names, MPM_NAMES_COUNT(topology_names), name);
}

const char *mpm_mesh_topology_name(int topology)
{
  return mpm_names_at(topology_names, MPM_NAMES_COUNT(topology_names), topology);
}

int mpm_mesh_diagonal_from_name(const char *name)
{
  return mpm_names_index(diagonal_names, MPM_NAMES_COUNT(diagonal_names), name);
}

const char *mpm_mesh_diagonal_name(int diagonal)
{
  return mpm_names_at(diagonal_names, MPM_NAMES_COUNT(diagonal_names), diagonal);
}

int mpm_mesh_from_config(mpm_mesh *m, const mpm_config *cfg, mpm_err *err)
{
  memset(m, 0, sizeof *m);
  m->nx = cfg->mesh.nx;
  m->ny = cfg->mesh.ny;
  m->x0 = cfg->mesh.x0;
  m->y0 = cfg->mesh.y0;
  m->dx = cfg->mesh.dx;
  m->dy = cfg->mesh.dy;
  m->topology = mpm_mesh_topology_from_name(cfg->mesh.topology);
  m->diagonal = mpm_mesh_diagonal_from_name(cfg->mesh.diagonal);
  m->mirror_x = cfg->mesh.mirror_x;
  m->periodic_x = cfg->bc.left == MPM_BC_PERIODIC;
  m->periodic_y = cfg->bc.bottom == MPM_BC_PERIODIC;
  if (m->topology < 0)
    return mpm_err_set(err, MPM_EINPUT, "mesh.topology '%s' unknown", cfg->mesh.topology);
  if (m->diagonal < 0)
    return mpm_err_set(err, MPM_EINPUT, "mesh.diagonal '%s' unknown", cfg->mesh.diagonal);
  return mpm_mesh_setup(m, err);
}

/* ---------------------------------------------------------------- nodes */

int mpm_mesh_node(const mpm_mesh *m, int i, int j)
{
  int is = mpm_mesh_in_axis_store(i, m->nx, m->periodic_x);
  int js = mpm_mesh_in_axis_store(j, m->ny, m->periodic_y);
  return js * m->snx + is;  /* id = j_s snx + i_s */
}

void mpm_mesh_node_pos(const mpm_mesh *m, int i, int j, double *x, double *y)
{
  *x = m->x0 + i * m->dx;
  *y = m->y0 + j * m->dy;
}

/* ------------------------------------------------------------- location */

double mpm_mesh_axis_wrap(double s, double len)
{
  if (!(s >= 0.0 && s < len)) {
    s -= len * floor(s / len);  /* s mod len */
    if (s >= len)
      s = 0.0;                  /* -tiny rounds to len: the same point */
  }
  return s;
}

void mpm_mesh_axis_wrap_coord(double *x, double o, double len)
{
  if (!isfinite(*x))
    return;
  double s = *x - o;
  if (!(s >= 0.0 && s < len))
    *x = o + mpm_mesh_axis_wrap(s, len);
}

void mpm_mesh_wrap(const mpm_mesh *m, double *x, double *y)
{
  if (m->periodic_x)
    mpm_mesh_axis_wrap_coord(x, m->x0, m->lx);
  if (m->periodic_y)
    mpm_mesh_axis_wrap_coord(y, m->y0, m->ly);
}

int mpm_mesh_unit(const mpm_mesh *m, double x, double y, int *i, int *j)
{
  double u, v;
  return mpm_mesh_locate(m, x, y, i, j, &u, &v) ? MPM_EOUTSIDE : MPM_OK;
}

int mpm_mesh_unit_is_slash(const mpm_mesh *m, int i, int j)
{
  (void)j;
  return mpm_mesh_column_is_slash(m, i);
}

/* ---------------------------------------------------------------- basis */

int mpm_mesh_basis(const mpm_mesh *m, double x, double y, int node[4],
                   double N[4], double dNx[4], double dNy[4])
{
  int i, j;
  double u, v;
  if (mpm_mesh_locate(m, x, y, &i, &j, &u, &v))
    return -1;
  return mpm_mesh_basis_at(m, i, j, u, v, node, N, dNx, dNy);
}
