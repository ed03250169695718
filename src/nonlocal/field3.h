/* field3.h: the element fluidity field on the 3D unit grid (the 3D module;
 * MODEL.md section 5 steps 1-2 on boxes, [DK-silo] §5.2 (ii), eq. 5.1):
 * the 7-point Laplacian with the ghost rules of 2D and its backward-Euler
 * solve, the code of the 2D field (grid.h, implicit.h) on a grid of three
 * axes.
 *
 * Units are the boxes of an mpm_mesh3, unit (i, j, k) at e = i + nx (j + ny k).
 * Given g_e and whether each unit is filled (sm_e > 0: its dense mass, or 1
 * and 0 as flags),
 *   lap_e = (g_{i+1} - 2 g_e + g_{i-1})/dx^2 + (g_{j+1} - 2 g_e + g_{j-1})/dy^2
 *         + (g_{k+1} - 2 g_e + g_{k-1})/dz^2
 * with ghosts across the six faces -x, +x, -y, +y, -z, +z of the mesh
 * (enum mpm_nonlocal_ghost: Neumann g_ghost = g_e, Dirichlet g_ghost = -g_e,
 * periodic wrap) and across every face to an empty unit (Neumann); empty
 * units get lap_e = 0. The implicit step solves (I - c L_h) g* = g_e on the
 * filled units with the same rows as 2D, through src/linalg (CHOLMOD; the
 * analysis kept while the filled set holds, the factor while c and the
 * rules do too), and gives lap_e = (g*_e - g_e)/c.
 *
 * The points enter by their centres (mpm_nonlocal3_average): g_e is the
 * mass-weighted mean g of the dense points whose centre lies in unit e (the
 * plane's "centre" rule), or by their extents (mpm_nonlocal3_average_parts,
 * the plane's "extent" rule): each point's mass split between the units its
 * box overlaps (mpm_nonlocal_grid_parts, 8 per point). The plane's unit
 * pressures have no 3D counterpart yet. */
#ifndef MPM_NONLOCAL_FIELD3_H
#define MPM_NONLOCAL_FIELD3_H

#include "core/error.h"
#include "linalg/linalg.h"
#include "mesh/box.h"
#include "nonlocal/grid.h"
#include "nonlocal/implicit.h"

typedef struct mpm_nonlocal3 {
  mpm_nonlocal_grid grid;      /* the unit grid: nx ny nz units, 1/h^2, six face rules */
  double *sm;                  /* [nu] dense mass of each unit [kg], or 1/0: filled when > 0 */
  double *ge;                  /* [nu] element fluidity g_e [1/s] */
  double *lap;                 /* [nu] lap_e [1/(m^2 s)] (0 when empty) */
  mpm_nonlocal_implicit *im;   /* the backward-Euler solver, made at its first use */
} mpm_nonlocal3;

/* Workspace for the units of mesh m (set up) with the ghost rules ghost[6]
 * of its faces -x, +x, -y, +y, -z, +z (enum mpm_nonlocal_ghost); periodic
 * faces come in pairs and agree with the mesh's periodic axes. sm, ge and
 * lap start at 0 (every unit empty). MPM_EINVAL / MPM_ENOMEM. */
int mpm_nonlocal3_alloc(mpm_nonlocal3 **out, const mpm_mesh3 *m, const int ghost[6],
                        mpm_err *err);
void mpm_nonlocal3_free(mpm_nonlocal3 *ws);   /* accepts NULL */

/* Index of unit (i, j, k). */
static inline size_t mpm_nonlocal3_unit(const mpm_nonlocal3 *ws, int i, int j, int k)
{
  const int c[3] = {i, j, k};
  return mpm_nonlocal_grid_index(&ws->grid, c);
}

/* ws->lap from ws->ge: the explicit 7-point Laplacian with ghost rules. */
void mpm_nonlocal3_laplacian(mpm_nonlocal3 *ws);

/* ws->lap = (g* - g_e)/c from (I - c L_h) g* = ws->ge on the filled units
 * (0 on empty ones); c = 0: the explicit Laplacian. Errors as
 * mpm_nonlocal_implicit_grid (c < 0 or not finite, no filled unit, the
 * factorisation or the solve), and MPM_ENOMEM for the solver's workspace. */
int mpm_nonlocal3_implicit(mpm_nonlocal3 *ws, double c, mpm_err *err);

/* g*_e of the last implicit solve ([nu], 0 on units empty then); NULL before
 * the first. */
const double *mpm_nonlocal3_gstar(const mpm_nonlocal3 *ws);

/* sm_e = sum m_p and g_e = sum m_p g_p / sm_e over the dense points p of
 * [0, n) with unit[p] = e (in point order, so thread-count free); 0 on the
 * other units. */
void mpm_nonlocal3_average(mpm_nonlocal3 *ws, size_t n, const int *unit, const double *mass,
                           const double *g, const unsigned char *dense);

/* The extent rule: as mpm_nonlocal3_average with each dense point's mass m_p
 * split by the weights w[8 p ...] between its units part[8 p ...]
 * (mpm_nonlocal_grid_parts): sm_e = sum w_pe m_p, g_e = sum w_pe m_p g_p /
 * sm_e. */
enum { MPM_NONLOCAL3_PARTS = 8 };
void mpm_nonlocal3_average_parts(mpm_nonlocal3 *ws, size_t n, const int *part, const double *w,
                                 const double *mass, const double *g,
                                 const unsigned char *dense);

/* 1 if some unit is filled (sm_e > 0). */
int mpm_nonlocal3_filled(const mpm_nonlocal3 *ws);

/* The implicit solver's counters (zero before its first use). */
mpm_linalg_stats mpm_nonlocal3_stats(const mpm_nonlocal3 *ws);

#endif
