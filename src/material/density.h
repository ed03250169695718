/* density.h: the density a point's state is decided with ([D-thesis] §3.4;
 * the rules are described at the top of density.c). The trans-phase models
 * read it as rho_{n+1}: below rho_c a point is stress-free. */
#ifndef MPM_MATERIAL_DENSITY_H
#define MPM_MATERIAL_DENSITY_H

#include <stddef.h>

#include "core/error.h"
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
  int nx, ny, nz;       /* units (nz = 1 in the plane) */
  int periodic[3];      /* periodic axes x, y, z */
  double area;          /* V_e = dx dy [m^2] (per unit thickness), dx dy dz in 3D */
  double *sm;           /* [nx*ny*nz] m_e: mass of the points in the unit [kg/m] */
  double *sv;           /* [nx*ny*nz] unit rule: volume of the points in the unit [m^2] */
  int *count;           /* [nx*ny*nz] number of points in the unit */
  unsigned char *edge;  /* [nx*ny*nz] hybrid: 1 for a boundary unit (a unit with
                           points and an empty unit among its 8 neighbours, 26 in 3D) */
} mpm_material_density;

/* Workspace for mesh m (set up). */
int mpm_material_density_alloc(mpm_material_density **out, const mpm_mesh *m, mpm_err *err);

/* Workspace for a grid of n[0] x n[1] x n[2] units of volume `volume` with
 * the periodic axes periodic[3], for a caller that gives every point's unit
 * (the 3D step's boxes, e = i + nx (j + ny k)): every rule. */
int mpm_material_density_alloc_grid(mpm_material_density **out, const int n[3],
                                    const int periodic[3], double volume, mpm_err *err);
void mpm_material_density_free(mpm_material_density *ws);  /* accepts NULL */

/* rho[p] for the n points at (x, y) with mass and volume vol, by rule (enum
 * mpm_material_density_rule; ws may be NULL for MPM_DENSITY_POINT). unit[p]
 * is the unit of point p, i + nx j (+ nx ny k), or -1 outside the mesh, when the caller
 * has it (the solver's nonlocal phase: one unit index per point per step);
 * NULL: from (x, y). A point outside the mesh is not counted in any unit and
 * gets m_p / V_p. m is the plane mesh (its periodic axes are the hybrid
 * rule's); NULL for a workspace of mpm_material_density_alloc_grid, whose
 * axes are its own. */
void mpm_material_density_compute(mpm_material_density *ws, const mpm_mesh *m, int rule,
                                  size_t n, const double *x, const double *y, const int *unit,
                                  const double *mass, const double *vol, double *rho);

#endif
