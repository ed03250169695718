/* density.h: the density a point's state is decided with ([D-thesis] §3.4;
 * the rules are described at the top of density.c). The trans-phase models
 * read it as rho_{n+1}: below rho_c a point is stress-free. */
#ifndef MPM_MATERIAL_DENSITY_H
#define MPM_MATERIAL_DENSITY_H

#include <stddef.h>

#include "core/error.h"
#include "core/points.h"
#include "mesh/mesh.h"

/* Which density decides a point's state (rho < rho_c: stress-free). */
enum mpm_material_density_rule {
  MPM_DENSITY_POINT = 0,  /* m_p / V_p, V_p from the local update [DK15] */
  MPM_DENSITY_ELEMENT,   /* m_e / (dx dy) of the unit holding the point's centre */
  MPM_DENSITY_HYBRID,    /* point in boundary units, element in the interior */
  MPM_DENSITY_UNIT       /* sum m_p / sum V_p over the points of the unit */
};

/* "point" | "element" | "hybrid" | "unit" <-> enum mpm_material_density_rule;
 * -1 / NULL if unknown. */
int mpm_material_density_rule_from_name(const char *name);
const char *mpm_material_density_rule_name(int rule);

/* Per-unit workspace of the element, hybrid and unit rules. */
typedef struct mpm_material_density {
  int n[3];             /* units along each axis (n[2] = 1 in the plane) */
  int periodic[3];      /* periodic axes x, y, z */
  double volume;        /* V_e = dx dy [m^2] (per unit thickness), dx dy dz in 3D */
  double *sm;           /* [nu] m_e: mass of the points in the unit */
  double *sv;           /* [nu] unit rule: volume of the points in the unit */
  int *count;           /* [nu] number of points in the unit */
  unsigned char *edge;  /* [nu] hybrid: 1 for a boundary unit (a unit with
                           points and an empty unit among its 8 neighbours, 26 in 3D) */
} mpm_material_density;

/* Workspace for the units of mesh m (set up), either dimension. */
int mpm_material_density_alloc(mpm_material_density **out, const mpm_mesh *m, mpm_err *err);
void mpm_material_density_free(mpm_material_density *ws);  /* accepts NULL */

/* rho[p] for the points of P on mesh m by rule (enum
 * mpm_material_density_rule; ws may be NULL for MPM_DENSITY_POINT). unit[p]
 * is the unit of point p (mpm_mesh_unit_index), or -1 outside the mesh, when
 * the caller has it (one unit index per point per step); NULL: from the
 * positions. A point outside the mesh is not counted in any unit and gets
 * m_p / V_p. */
void mpm_material_density_compute(mpm_material_density *ws, const mpm_mesh *m, int rule,
                                  const mpm_points *P, const int *unit, double *rho);

#endif
