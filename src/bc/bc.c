/* bc.c: edge boundary conditions as a per-node mask (MODEL.md section 2, step 3).
 * No-slip fixes both velocity components of every node on the edge;
 * frictionless and symmetry fix the normal one. */
#include "bc/bc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/config.h"
#include "core/names.h"
#include "bc/bc_internal.h"

static const char *const bc_names[] = {
  [MPM_BC_FREE] = "free",
  [MPM_BC_NOSLIP] = "noslip",
  [MPM_BC_FRICTIONLESS] = "frictionless",
  [MPM_BC_SYMMETRY] = "symmetry",
  [MPM_BC_PERIODIC] = "periodic",
};

static const char *const edge_names[] = {"left", "right", "bottom", "top"};
static const char *const wall_acceleration_names[] = {"jump", "zero"};

int mpm_bc_wall_acceleration_from_name(const char *name)
{
  return mpm_names_index(wall_acceleration_names, MPM_NAMES_COUNT(wall_acceleration_names), name);
}

const char *mpm_bc_wall_acceleration_name(int rule)
{
  return mpm_names_at(wall_acceleration_names, MPM_NAMES_COUNT(wall_acceleration_names), rule);
}

int mpm_bc_kind_from_name(const char *name)
{
  return mpm_names_index(bc_names, MPM_NAMES_COUNT(bc_names), name);
}

const char *mpm_bc_kind_name(int kind)
{
  return mpm_names_at(bc_names, MPM_NAMES_COUNT(bc_names), kind);
}

/* Mask bits an edge of a given kind sets: its normal is x on left/right
 * (MPM_EDGE_* / 2 is the normal's axis). */
static unsigned char edge_bits(int kind, int edge)
{
  return mpm_bc_wall_bits(kind, edge / 2, 2);
}

int mpm_bc_check_kinds(const int *kind, int dim, const int *periodic,
                       const char *const *names, const char *what, mpm_err *err)
{
  for (int e = 0; e < 2 * dim; e++)
    if (!mpm_bc_kind_name(kind[e]))
      return mpm_err_set(err, MPM_EINVAL, "boundary '%s': unknown kind %d", names[e], kind[e]);
  for (int a = 0; a < dim; a++) {
    const int lo = kind[2 * a] == MPM_BC_PERIODIC, hi = kind[2 * a + 1] == MPM_BC_PERIODIC;
    if (lo != hi)
      return mpm_err_set(err, MPM_EINPUT, "boundary: '%s' and '%s' must both be periodic or neither",
                         names[2 * a], names[2 * a + 1]);
  }
  for (int a = 0; a < dim; a++)
    if ((kind[2 * a] == MPM_BC_PERIODIC) != (periodic[a] != 0))
      return mpm_err_set(err, MPM_EINVAL, "boundary: periodic %s disagree with the mesh", what);
  return MPM_OK;
}

int mpm_bc_setup(mpm_bc *bc, const mpm_mesh *m, const int edge[4], mpm_err *err)
{
  const int periodic[2] = {m->periodic_x, m->periodic_y};
  int rc = mpm_bc_check_kinds(edge, 2, periodic, edge_names, "edges", err);
  if (rc != MPM_OK)
    return rc;

  memcpy(bc->edge, edge, sizeof bc->edge);
  bc->nnodes = m->nnodes;
  bc->out_edge = -1;
  bc->open = 0;
  bc->mask[1] = NULL;
  bc->normal = NULL;
  bc->fix = bc->mask[0] = calloc((size_t)m->nnodes, 1);
  if (!bc->fix)
    return mpm_err_set(err, MPM_ENOMEM, "boundary mask: out of memory");
  for (int j = 0; j <= m->ny; j++) {
    bc->fix[mpm_mesh_node(m, 0, j)] |= edge_bits(edge[MPM_EDGE_LEFT], MPM_EDGE_LEFT);
    bc->fix[mpm_mesh_node(m, m->nx, j)] |= edge_bits(edge[MPM_EDGE_RIGHT], MPM_EDGE_RIGHT);
  }
  for (int i = 0; i <= m->nx; i++) {
    bc->fix[mpm_mesh_node(m, i, 0)] |= edge_bits(edge[MPM_EDGE_BOTTOM], MPM_EDGE_BOTTOM);
    bc->fix[mpm_mesh_node(m, i, m->ny)] |= edge_bits(edge[MPM_EDGE_TOP], MPM_EDGE_TOP);
  }
  return MPM_OK;
}

void mpm_bc_clear(mpm_bc *bc)
{
  free(bc->mask[0]);
  free(bc->mask[1]);
  free(bc->normal);
  bc->fix = bc->mask[0] = bc->mask[1] = NULL;
  bc->normal = NULL;
  bc->nnodes = 0;
}

void mpm_bc_apply(const mpm_bc *bc, double *ax, double *ay)
{
  for (int i = 0; i < bc->nnodes; i++)
    mpm_bc_apply_node(bc, i, &ax[i], &ay[i]);
}

void mpm_bc_clamp(const mpm_bc *bc, const mpm_mesh *m, double *x, double *y, double *vx,
                  double *vy, double gvx, double gvy)
{
  if (mpm_bc_left_through_outlet(bc, m, *x, *y))
    return;                                  /* leaves through the open outlet */
  mpm_bc_clamp_axis(x, vx, gvx, m->x0, m->x0 + m->lx, mpm_bc_is_wall(bc->edge[MPM_EDGE_LEFT]),
                    mpm_bc_is_wall(bc->edge[MPM_EDGE_RIGHT]));
  mpm_bc_clamp_axis(y, vy, gvy, m->y0, m->y0 + m->ly, mpm_bc_is_wall(bc->edge[MPM_EDGE_BOTTOM]),
                    mpm_bc_is_wall(bc->edge[MPM_EDGE_TOP]));
}
