/* implicit.h: backward-Euler diffusion of the element fluidity (docs/model.md,
 * "Implicit diffusion").
 *
 * The explicit scheme gives a point g* = g_n + c lap_e with c = k A^2 d^2,
 * k = dt_sub / t0, lap_e = L_h g_e the 5-point Laplacian with ghost rules
 * (nonlocal.h). The implicit one solves, on the filled units,
 *   (I - c L_h) g* = g_e,
 * L_h the same operator with the same ghosts (mpm_nonlocal_grid_side), and hands
 * the points lap_e = (g*_e - g_e) / c, which equals L_h g*_e: the points and
 * the material update (g* = g_n + c lap) are unchanged, only lap_e is taken
 * at the new level. The matrix is symmetric positive definite (see
 * docs/model.md); it is factored with CHOLMOD through src/linalg and kept.
 * Its rows are the units filled at any solve so far (empty ones as identity
 * rows, implicit.c), so the symbolic analysis is redone only when material
 * reaches a unit for the first time, the numeric factorisation when the
 * filled set, c or the ghost rules change; otherwise only the solve runs.
 * c = 0 gives the explicit lap_e.
 *
 * Usage per (sub)step, after mpm_nonlocal_average (instead of
 * mpm_nonlocal_laplacian):
 *   mpm_nonlocal_implicit_laplacian(im, ws, k * A * A * d * d, err);
 * On an error the caller adds the step and the time to err.
 *
 * The solve is written for the unit grid of grid.h, in 2 or 3 dimensions
 * (the 5- or 7-point operator; its rows from mpm_nonlocal_grid_row): the 2D
 * workspace calls it with its grid, the 3D field (field3.h) with its own. */
#ifndef MPM_NONLOCAL_IMPLICIT_H
#define MPM_NONLOCAL_IMPLICIT_H

#include "core/error.h"
#include "linalg/linalg.h"
#include "nonlocal/nonlocal.h"

typedef struct mpm_nonlocal_implicit mpm_nonlocal_implicit;   /* opaque */

/* Solver workspace for the unit grid of ws (its size is kept: use it with
 * that workspace only). NULL (and err set) when out of memory. */
mpm_nonlocal_implicit *mpm_nonlocal_implicit_alloc(const mpm_nonlocal *ws, mpm_err *err);

/* The same for a unit grid g of 2 or 3 dimensions. */
mpm_nonlocal_implicit *mpm_nonlocal_implicit_alloc_grid(const mpm_nonlocal_grid *g,
                                                        mpm_err *err);
void mpm_nonlocal_implicit_free(mpm_nonlocal_implicit *im);   /* accepts NULL */

/* From ws->ge on the filled units (ws->sm > 0): g* of (I - c L_h) g* = g_e,
 * then ws->lap[e] = (g*_e - g_e) / c on filled units and 0 on empty ones.
 * c = 0: ws->lap from mpm_nonlocal_laplacian (the factor is left alone).
 * Errors: MPM_EINVAL for c < 0 or not finite, for no filled unit, or a grid
 * other than the one allocated for; MPM_ESOLVE / MPM_ENONFINITE from the
 * factorisation or the solve, naming the number of filled units and c.
 * ws->lap is untouched on error. */
int mpm_nonlocal_implicit_laplacian(mpm_nonlocal_implicit *im, mpm_nonlocal *ws, double c,
                                    mpm_err *err);

/* The same on grid g (the one allocated for, same dimension and units) with
 * unit arrays sm (filled when > 0), ge and lap of g->nu entries each:
 * (I - c L_h) g* = ge on the filled units, lap[e] = (g*_e - ge_e)/c there and
 * 0 elsewhere; c = 0: lap from mpm_nonlocal_grid_laplacian. Errors as above. */
int mpm_nonlocal_implicit_grid(mpm_nonlocal_implicit *im, const mpm_nonlocal_grid *g,
                               const double *sm, const double *ge, double *lap, double c,
                               mpm_err *err);

/* g*_e of the last solve ([nu], 0 on units empty then); valid until the
 * next call. */
const double *mpm_nonlocal_implicit_gstar(const mpm_nonlocal_implicit *im);

/* Counts of analyses, factorisations and solves, and whether the last
 * factor fell back to QR (the matrix was not found positive definite). */
mpm_linalg_stats mpm_nonlocal_implicit_stats(const mpm_nonlocal_implicit *im);

#endif
