/* box.h: the mesh of boxes the 3D mesh and shape tests share: a set-up
 * mesh with distinct unit sizes and an offset origin, and the logical
 * indices and nearest periodic image of a storage node. */
#ifndef TESTS_BOX_H
#define TESTS_BOX_H

#include <check.h>
#include <math.h>
#include <string.h>

#include "core/error.h"
#include "mesh/mesh.h"

/* nx x ny x nz boxes of 0.13 x 0.11 x 0.12 from (-0.4, 0.25, 0.1); periodic
 * axes from the bits of per (x: 1, y: 2, z: 4). */
static inline mpm_mesh make_box(int nx, int ny, int nz, int per)
{
  mpm_mesh m;
  memset(&m, 0, sizeof m);
  m.dim = 3;
  m.nx = nx;
  m.ny = ny;
  m.nz = nz;
  m.x0 = -0.4;
  m.y0 = 0.25;
  m.z0 = 0.1;
  m.dx = 0.13;
  m.dy = 0.11;
  m.dz = 0.12;
  m.topology = MPM_TOPO_Q4;
  m.periodic_x = per & 1;
  m.periodic_y = per >> 1 & 1;
  m.periodic_z = per >> 2 & 1;
  mpm_err err = {0};
  ck_assert_msg(mpm_mesh_setup(&m, &err) == MPM_OK, "%s", err.msg);
  return m;
}

/* Logical indices of storage node id. */
static inline void box_node_ijk(const mpm_mesh *m, int id, int ijk[3])
{
  ijk[0] = id % m->snx;
  ijk[1] = id / m->snx % m->sny;
  ijk[2] = id / (m->snx * m->sny);
}

/* Position of storage node id shifted by whole periods to lie nearest xp. */
static inline void box_node_near(const mpm_mesh *m, int id, const double xp[3], double x[3])
{
  int ijk[3];
  box_node_ijk(m, id, ijk);
  mpm_mesh_node_pos(m, ijk[0], ijk[1], ijk[2], x);
  for (int d = 0; d < 3; d++)
    if (m->periodic[d])
      x[d] += m->len[d] * round((xp[d] - x[d]) / m->len[d]);
}

#endif
