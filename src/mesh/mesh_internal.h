/* mesh_internal.h: what the 2D mesh (mesh.c) and the 3D mesh (box.c) share,
 * per axis and so dimension-agnostic: the checks of one axis's units and
 * lengths, and the storage index of a logical node along one axis. Not
 * part of the library's interface (names mpm_mesh_in_*). */
#ifndef MPM_MESH_MESH_INTERNAL_H
#define MPM_MESH_MESH_INTERNAL_H

#include "core/error.h"

/* Units along one axis: n >= 1 (and room for n + 1 nodes), periodic flag
 * 0/1, n >= nper when periodic (1 on the plane mesh, 2 on the 3D box).
 * MPM_EINPUT names mesh.n<axis>. */
int mpm_mesh_in_check_units(int n, int periodic, int nper, char axis, mpm_err *err);

/* Origin finite, unit size finite and > 0, domain end finite. */
int mpm_mesh_in_check_lengths(int n, double o, double h, char axis, mpm_err *err);

/* Logical index k along an axis of n units -> stored index (k mod n if periodic). */
static inline int mpm_mesh_in_axis_store(int k, int n, int periodic)
{
  if (!periodic)
    return k;
  k %= n;
  return k < 0 ? k + n : k;
}

#endif
