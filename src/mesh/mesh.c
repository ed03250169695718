/* mesh.c: the structured background mesh of 2 or 3 dimensions (MODEL.md
 * section 3).
 *
 * Validation of the caller's fields axis by axis, node numbering with
 * periodic aliasing (storage id = (k_s sny + j_s) snx + i_s, i_s = i mod nx
 * along a periodic x), unit lookup, and the element basis at a position:
 * bilinear Q4 or linear T3 on the half of the unit cut by its diagonal
 * ("/", "\", or "mirror" about x = mirror_x, [DK-silo] 7.1) in the plane,
 * trilinear on boxes. The basis is in the hot loop: no allocation, no
 * division. */
#include "mesh/mesh.h"

#include <limits.h>
#include <math.h>
#include <string.h>

#include "core/names.h"

/* ---------------------------------------------------------------- setup */

static const char axis_name[3] = {'x', 'y', 'z'};

/* Units along axis a: n >= 1, periodic flag 0/1, n >= nper when periodic. */
static int check_units(int n, int periodic, int nper, int a, mpm_err *err)
{
  const char c = axis_name[a];
  if (periodic != 0 && periodic != 1)
    return mpm_err_set(err, MPM_EINPUT,
                       "mesh.periodic_%c = %d is out of range (allowed: 0 or 1)", c, periodic);
  if (n < 1 || n > INT_MAX - 1)
    return mpm_err_set(err, MPM_EINPUT,
                       "mesh.n%c = %d is out of range (allowed: integer >= 1)", c, n);
  if (periodic && n < nper)
    return mpm_err_set(err, MPM_EINPUT,
                       "mesh.n%c = %d is out of range (allowed: n%c >= %d when %c "
                       "is periodic)", c, n, c, nper, c);
  return MPM_OK;
}

/* Origin finite, unit size finite and > 0, domain end finite. */
static int check_lengths(int n, double o, double h, int a, mpm_err *err)
{
  const char c = axis_name[a];
  if (!isfinite(o))
    return mpm_err_set(err, MPM_EINPUT, "mesh.%c0 = %g is out of range (allowed: finite) [m]",
                       c, o);
  if (!(h > 0.0) || !isfinite(h))
    return mpm_err_set(err, MPM_EINPUT,
                       "mesh.d%c = %g is out of range (allowed: finite, > 0) [m]", c, h);
  if (!isfinite(o + n * h))
    return mpm_err_set(err, MPM_EINPUT, "mesh.%c0 + mesh.n%c * mesh.d%c = %g is not finite [m]",
                       c, c, c, o + n * h);
  return MPM_OK;
}

/* Topology, diagonal rule, mirror line. */
static int check_topology(const mpm_mesh *m, mpm_err *err)
{
  if (m->topology != MPM_TOPO_Q4 && m->topology != MPM_TOPO_T3)
    return mpm_err_set(err, MPM_EINPUT,
                       "mesh.topology = %d is out of range (allowed: %d = q4, "
                       "%d = t3)", m->topology, MPM_TOPO_Q4, MPM_TOPO_T3);
  if (m->dim == 3 && m->topology != MPM_TOPO_Q4)
    return mpm_err_set(err, MPM_EINPUT, "mesh.topology = \"t3\" is plane only (allowed in 3D: "
                       "\"q4\", the trilinear box)");
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
  if (m->dim == 0)
    m->dim = 2;
  if (m->dim != 2 && m->dim != 3)
    return mpm_err_set(err, MPM_EINPUT, "mesh: dimension %d (allowed: 2 or 3)", m->dim);
  if (m->dim == 2) {                 /* the absent axis: one unit of unit thickness */
    m->nz = 1;
    m->z0 = 0.0;
    m->dz = 1.0;
    m->periodic_z = 0;
  }
  /* a periodic axis of one unit is one node row or column: its two edges
   * are one node, so nothing varies along it (the infinite layer of [DK15]
   * section 4.4 and [DK-silo] section 6 on one column of elements); a box
   * needs two (a unit must not be its own neighbour across a face) */
  const int nper = m->dim == 3 ? 2 : 1;
  int rc;
  for (int a = 0; a < m->dim; a++)
    if ((rc = check_units(m->n[a], m->periodic[a], nper, a, err)) != MPM_OK)
      return rc;
  for (int a = 0; a < m->dim; a++)
    if ((rc = check_lengths(m->n[a], m->o[a], m->h[a], a, err)) != MPM_OK)
      return rc;
  if ((rc = check_topology(m, err)) != MPM_OK)
    return rc;
  long long nn = 1;
  for (int a = 0; a < 3; a++) {
    m->sn[a] = m->periodic[a] || (a == 2 && m->dim == 2) ? m->n[a] : m->n[a] + 1;
    nn = nn <= INT_MAX ? nn * m->sn[a] : nn;            /* < 2^62: no overflow */
  }
  if (nn > INT_MAX) {
    if (m->dim == 2)
      return mpm_err_set(err, MPM_EINPUT, "mesh.nx = %d, mesh.ny = %d: %lld nodes is out of "
                         "range (allowed: at most %d)", m->nx, m->ny, nn, INT_MAX);
    return mpm_err_set(err, MPM_EINPUT, "mesh.nx = %d, mesh.ny = %d, mesh.nz = %d: too many "
                       "nodes (allowed: at most %d)", m->nx, m->ny, m->nz, INT_MAX);
  }
  m->nnodes = (int)nn;
  m->nunits = (size_t)m->nx * (size_t)m->ny * (size_t)m->nz;
  for (int a = 0; a < 3; a++) {
    m->len[a] = m->n[a] * m->h[a];
    m->ih[a] = 1.0 / m->h[a];
  }
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
  const int three = cfg->mesh.nz > 0;
  m->dim = three ? 3 : 2;
  m->nx = cfg->mesh.nx;
  m->ny = cfg->mesh.ny;
  m->x0 = cfg->mesh.x0;
  m->y0 = cfg->mesh.y0;
  m->dx = cfg->mesh.dx;
  m->dy = cfg->mesh.dy;
  if (three) {
    m->nz = cfg->mesh.nz;
    m->z0 = cfg->mesh.z0;
    m->dz = cfg->mesh.dz;
    m->periodic_z = cfg->bc.front == MPM_BC_PERIODIC;
  }
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

/* Logical index k along an axis of n units -> stored index (k mod n if periodic). */
static int axis_store(int k, int n, int periodic)
{
  if (!periodic)
    return k;
  k %= n;
  return k < 0 ? k + n : k;
}

int mpm_mesh_node(const mpm_mesh *m, int i, int j, int k)
{
  const int is = axis_store(i, m->nx, m->periodic_x);
  const int js = axis_store(j, m->ny, m->periodic_y);
  const int ks = axis_store(k, m->nz, m->periodic_z);
  return (ks * m->sny + js) * m->snx + is;  /* id = (k_s sny + j_s) snx + i_s */
}

void mpm_mesh_node_pos(const mpm_mesh *m, int i, int j, int k, double x[3])
{
  x[0] = m->x0 + i * m->dx;
  x[1] = m->y0 + j * m->dy;
  x[2] = m->dim == 3 ? m->z0 + k * m->dz : 0.0;
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

void mpm_mesh_wrap(const mpm_mesh *m, double x[3])
{
  for (int a = 0; a < m->dim; a++)
    if (m->periodic[a])
      mpm_mesh_axis_wrap_coord(&x[a], m->o[a], m->len[a]);
}

int mpm_mesh_unit(const mpm_mesh *m, const double x[3], int c[3])
{
  double l[3];
  return mpm_mesh_locate(m, x, c, l) ? MPM_EOUTSIDE : MPM_OK;
}

/* ---------------------------------------------------------------- basis */

int mpm_mesh_basis(const mpm_mesh *m, const double x[3], int *node, double *N,
                   double *const dN[3])
{
  int c[3];
  double l[3];
  if (mpm_mesh_locate(m, x, c, l))
    return -1;
  return mpm_mesh_basis_at(m, c, l, node, N, dN);
}
