/* field.h: one (sub)step of the NGF element field for the solver (MODEL.md
 * section 5 steps 1-2, [DK-silo] §5.2 (i)-(ii)), the steady field of one step
 * (MODEL.md section 6, [D-thesis] §3.5.2), and the table of fluidity solvers
 * they choose from.
 *
 * Per (sub)step of length dt_sub, with the points' units frozen
 * (mpm_nonlocal_locate_extents):
 *   1. dense flags from the model (mpm_material_type.dense: p_n > 0,
 *      rho_{n+1} >= rho_c for NGF) and the point pressures p_n;
 *   2. g_e over the dense points (mpm_nonlocal_average);
 *   3. lap_e by the diffusion solver, c = (dt_sub / t0) A^2 d^2:
 *        explicit: lap_e = L_h g_e (mpm_nonlocal_laplacian), stable only
 *                  when c (2/dx^2 + 2/dy^2) <= 1 (mpm_material_ngf_diffusion_number);
 *        implicit: lap_e = L_h g*, (I - c L_h) g* = g_e (implicit.h), for
 *                  any c;
 *      either way a point then takes g* = g_n + c lap_e (the model's update);
 *   4. the unit p^-1/2 when the model samples it per unit (mpm_nonlocal_pressure).
 * The solvers are a const table indexed by enum mpm_nonlocal_diffusion_kind
 * (material.diffusion); a solver's state (the implicit factorisation) lives
 * in the workspace and is freed with it.
 *
 * The steady solver (`steady`) has no time scale and no unit grid: once per
 * MPM step, before the points move, mpm_nonlocal_steady_field solves the
 * steady equation on the mesh nodes from the stress at the start of the step
 * (steady.h) and sets every point's g to the value it reads there; the
 * model's update_steady then takes that g as g_{n+1} in every substep. Its
 * table entry has .steady = 1 and no laplacian. */
#ifndef MPM_NONLOCAL_FIELD_H
#define MPM_NONLOCAL_FIELD_H

#include "core/error.h"
#include "core/points.h"
#include "linalg/linalg.h"
#include "material/material.h"
#include "nonlocal/nonlocal.h"
#include "shape/shape.h"

/* material.diffusion */
enum mpm_nonlocal_diffusion_kind {
  MPM_DIFFUSION_EXPLICIT = 0,
  MPM_DIFFUSION_IMPLICIT,
  MPM_DIFFUSION_STEADY
};

typedef struct mpm_nonlocal_diffusion {
  const char *name;         /* as written in the input */
  const char *description;
  int stability_limited;    /* 1: needs c (2/dx^2 + 2/dy^2) <= 1 per substep */
  int steady;               /* 1: g solved for once per step on the nodes
                               (mpm_nonlocal_steady_field), not diffused: no
                               laplacian, no seeding, the model's update_steady */
  /* State for the unit grid of ws (NULL state: none needed); MPM_OK or an error. */
  int (*alloc)(void **state, const mpm_nonlocal *ws, mpm_err *err);
  void (*free)(void *state);
  /* lap_e on every unit from ws->ge for diffusivity c (0 on empty units);
   * NULL for the steady solver. */
  int (*laplacian)(void *state, mpm_nonlocal *ws, double c, mpm_err *err);
} mpm_nonlocal_diffusion;

/* Indexed by enum mpm_nonlocal_diffusion_kind, NULL ended. */
extern const mpm_nonlocal_diffusion *const mpm_nonlocal_diffusion_table[];

/* "explicit" | "implicit" | "steady" <-> enum mpm_nonlocal_diffusion_kind;
 * -1 / NULL if unknown. */
int mpm_nonlocal_diffusion_from_name(const char *name);
const char *mpm_nonlocal_diffusion_name(int kind);

/* Use solver `kind` in ws from now on (allocates its state; the default of
 * a new workspace is explicit). MPM_EINVAL for an unknown kind. */
int mpm_nonlocal_set_diffusion(mpm_nonlocal *ws, int kind, mpm_err *err);

/* Steps 1-4 above for the n = P->n points of model mt with parameters par
 * over dt_sub; rho[p] is the density of each point's state decision (NULL:
 * mass / vol); local: lap_e = 0 (a model without a seeding model before
 * t_seed: material.h). Afterwards mpm_nonlocal_point_lap and
 * mpm_nonlocal_point_isp give each point its inputs. Errors come from the
 * diffusion solver. */
int mpm_nonlocal_field(mpm_nonlocal *ws, const mpm_material_type *mt,
                       const mpm_material_params *par, const mpm_points *P, const double *rho,
                       double dt_sub, int local, mpm_err *err);

/* 1 if ws uses the steady solver. */
int mpm_nonlocal_is_steady(const mpm_nonlocal *ws);

/* The steady field of one MPM step (steady.h) for the n = P->n points of
 * model mt (which must have steady_terms and update_steady) on mesh m, with
 * the step's stencil st (points at x_n): the dense points (state dense,
 * p_n > 0) give w = |F(mu_n)|/(A d)^2 and g_loc; the nodes of the
 * Dirichlet edges are held at 0 (mpm_nonlocal_held_nodes); then every
 * point's P->g becomes the value it reads (sample: enum
 * mpm_nonlocal_steady_sample; mass: enum mpm_nonlocal_steady_mass). With
 * A = 0 there is nothing to solve: g = g_loc at the dense points, 0 at the
 * others (the local model). Errors from the solve (steady.h). */
int mpm_nonlocal_steady_field(mpm_nonlocal *ws, const mpm_material_type *mt,
                              const mpm_material_params *par, mpm_points *P,
                              const mpm_shape_stencil *st, const mpm_mesh *m, int sample,
                              int mass, mpm_err *err);

/* Statistics of the last steady solve (zero counters before the first). */
mpm_linalg_stats mpm_nonlocal_steady_field_stats(const mpm_nonlocal *ws);

/* Nodal g of the last steady field ([mesh nnodes]; 0 at the nodes that were
 * not unknowns), NULL before the first solve or with A = 0 (no nodal field). */
const double *mpm_nonlocal_steady_field_nodal(const mpm_nonlocal *ws);

#endif
