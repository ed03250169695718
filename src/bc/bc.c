/* bc.c: edge boundary conditions as a per-node mask (MODEL.md section 2, step 3).
 * No-slip fixes both velocity components of every node on the edge;
 * frictionless and symmetry fix the normal one. */
#include "bc/bc.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/config.h"
#include "core/names.h"

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

/* Mask bits an edge of a given kind sets; the normal of left/right edges is x. */
static unsigned char edge_bits(int kind, int edge)
{
  unsigned char normal = (edge == MPM_EDGE_LEFT || edge == MPM_EDGE_RIGHT) ? MPM_FIX_X : MPM_FIX_Y;
  switch (kind) {
  case MPM_BC_NOSLIP: return MPM_FIX_X | MPM_FIX_Y;
  case MPM_BC_FRICTIONLESS:
  case MPM_BC_SYMMETRY: return normal;
  default: return 0;
  }
}

int mpm_bc_setup(mpm_bc *bc, const mpm_mesh *m, const int edge[4], mpm_err *err)
{
  for (int e = 0; e < 4; e++)
    if (!mpm_bc_kind_name(edge[e]))
      return mpm_err_set(err, MPM_EINVAL, "boundary '%s': unknown kind %d", edge_names[e], edge[e]);
  int px = edge[MPM_EDGE_LEFT] == MPM_BC_PERIODIC, px2 = edge[MPM_EDGE_RIGHT] == MPM_BC_PERIODIC;
  int py = edge[MPM_EDGE_BOTTOM] == MPM_BC_PERIODIC, py2 = edge[MPM_EDGE_TOP] == MPM_BC_PERIODIC;
  if (px != px2)
    return mpm_err_set(err, MPM_EINPUT, "boundary: 'left' and 'right' must both be periodic or neither");
  if (py != py2)
    return mpm_err_set(err, MPM_EINPUT, "boundary: 'bottom' and 'top' must both be periodic or neither");
  if (px != m->periodic_x || py != m->periodic_y)
    return mpm_err_set(err, MPM_EINVAL, "boundary: periodic edges disagree with the mesh");

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

/* 1 if an edge of this kind is a wall that material cannot cross. */
static int is_wall(int kind)
{
  return kind == MPM_BC_NOSLIP || kind == MPM_BC_FRICTIONLESS || kind == MPM_BC_SYMMETRY;
}

void mpm_bc_clamp(const mpm_bc *bc, const mpm_mesh *m, double *x, double *y, double *vx,
                  double *vy, double gvx, double gvy)
{
  double xhi = m->x0 + m->lx, yhi = m->y0 + m->ly;
  if (mpm_bc_left_through_outlet(bc, m, *x, *y))
    return;                                  /* leaves through the open outlet */
  if (*x < m->x0 && is_wall(bc->edge[MPM_EDGE_LEFT])) {
    *x = m->x0;
    *vx = fmax(*vx, fmin(gvx, 0.0));
  }
  if (*x > xhi && is_wall(bc->edge[MPM_EDGE_RIGHT])) {
    *x = xhi;
    *vx = fmin(*vx, fmax(gvx, 0.0));
  }
  if (*y < m->y0 && is_wall(bc->edge[MPM_EDGE_BOTTOM])) {
    *y = m->y0;
    *vy = fmax(*vy, fmin(gvy, 0.0));
  }
  if (*y > yhi && is_wall(bc->edge[MPM_EDGE_TOP])) {
    *y = yhi;
    *vy = fmin(*vy, fmax(gvy, 0.0));
  }
}
