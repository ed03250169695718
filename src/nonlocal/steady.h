/* steady.h: the steady nonlocal fluidity by a Galerkin solve on the mesh
 * nodes ([D-thesis] section 3.5.2 and Algorithm 2; MODEL.md section 6).
 *
 * Per MPM step, from the stress at its start: each dense point p carries
 * w_p = 1/xi_p^2 = c_p / (A d)^2 and g_loc,p (the model's steady_terms, c_p =
 * |F(mu_p)|), and g solves
 *   lap(g) = (g - g_loc) / xi^2
 * with zero flux (d_n g = 0) on the boundary of the material except at the
 * nodes held at g = 0. With g = sum_j g_j S_j, tested with S_i and
 * integrated over the points (volumes V_p, the step's stencil S_ip, gradS_ip):
 *   sum_j A_ij g_j = b_i,
 *   A_ij = sum_p V_p (w_p S_ip S_jp + gradS_ip . gradS_jp),
 *   b_i  = sum_p V_p w_p S_ip g_loc,p,
 * the unknowns being the nodes the dense points touch, less the held ones
 * (their rows and columns removed: g = 0 there). The lumped variant replaces
 * w_p S_ip S_jp by its row sums, diag(sum_p V_p w_p S_ip) (sum_j S_jp = 1).
 *
 * A is symmetric positive semi-definite: g . A g = sum_p V_p (w_p (sum_i S_ip
 * g_i)^2 + |sum_i gradS_ip g_i|^2). It is definite unless a nodal vector is
 * invisible to every point: the constants are not (sum_i S_ip = 1, so
 * w_p > 0 at one point suffices), but with one point per unit placed at unit
 * centres the Q4 hourglass vector (+1, -1, +1, -1 around every unit) is, both
 * in S and in gradS; a held node breaks it, the lumped mass always does.
 * The matrix goes to CHOLMOD through src/linalg (the symbolic analysis only
 * when the pattern changed, i.e. when a point comes to touch a new pair of
 * nodes), with the CSparse QR fallback where Cholesky stops.
 *
 * A point then reads g where it is (mpm_nonlocal_steady_point): the mean of
 * the nodal g over the element containing it (MPM_STEADY_ELEMENT, the
 * [D-thesis] rows marked "*", default: g and gdot_p then have the order of
 * the velocity gradient, and the hourglass vector averages to zero) or
 * sum_i S_ip g_i (MPM_STEADY_LINEAR); negative values are read as 0. */
#ifndef MPM_NONLOCAL_STEADY_H
#define MPM_NONLOCAL_STEADY_H

#include <stddef.h>

#include "core/error.h"
#include "linalg/linalg.h"
#include "mesh/mesh.h"
#include "shape/shape.h"

/* material.g_sample: how a point reads the nodal solution. */
enum mpm_nonlocal_steady_sample { MPM_STEADY_ELEMENT = 0, MPM_STEADY_LINEAR };
/* material.g_mass: the w S S term, as written or lumped. */
enum mpm_nonlocal_steady_mass { MPM_STEADY_CONSISTENT = 0, MPM_STEADY_LUMPED };

/* "element" | "linear", "consistent" | "lumped" <-> the enums; -1 / NULL if unknown. */
int mpm_nonlocal_steady_sample_from_name(const char *name);
const char *mpm_nonlocal_steady_sample_name(int sample);
int mpm_nonlocal_steady_mass_from_name(const char *name);
const char *mpm_nonlocal_steady_mass_name(int mass);

typedef struct mpm_nonlocal_steady mpm_nonlocal_steady;   /* opaque */

/* A solver for mesh m (its node count is kept: use it with that mesh only);
 * NULL (and err set) when out of memory. */
mpm_nonlocal_steady *mpm_nonlocal_steady_alloc(const mpm_mesh *m, mpm_err *err);
void mpm_nonlocal_steady_free(mpm_nonlocal_steady *ss);   /* accepts NULL */

/* Assemble and solve for the n points of stencil st (on mesh m) with volumes vol, w = 1/xi^2
 * [1/m^2] and g_loc [1/s], the points with dense[p] != 0 taking part, the
 * nodes with held[i] != 0 at g = 0; mass is an enum mpm_nonlocal_steady_mass.
 * No unknown (no dense point, or all its nodes held): g = 0, MPM_OK.
 * Errors: MPM_EINVAL for a non-finite w V or w V g_loc (naming the point
 * index), MPM_ESOLVE when Cholesky and QR both fail, MPM_ENOMEM; the message
 * names the number of unknowns, the caller adds the step and the time. */
int mpm_nonlocal_steady_solve(mpm_nonlocal_steady *ss, const mpm_shape_stencil *st,
                              const mpm_mesh *m, size_t n, const double *vol, const double *w,
                              const double *gloc, const unsigned char *dense,
                              const unsigned char *held, int mass, mpm_err *err);

/* Nodal g of the last solve ([mesh nnodes], 0 at nodes that are not unknowns). */
const double *mpm_nonlocal_steady_nodal(const mpm_nonlocal_steady *ss);

/* Number of unknowns of the last solve. */
int mpm_nonlocal_steady_unknowns(const mpm_nonlocal_steady *ss);

/* g at point p of store P (its stencil st on mesh m), read as sample says
 * (enum mpm_nonlocal_steady_sample), max(0, .); 0 outside the mesh. */
double mpm_nonlocal_steady_point(const mpm_nonlocal_steady *ss, const mpm_mesh *m,
                                 const mpm_shape_stencil *st, const mpm_points *P, size_t p,
                                 int sample);

/* Counts of analyses, factorisations (and QR fallbacks) and solves. */
mpm_linalg_stats mpm_nonlocal_steady_stats(const mpm_nonlocal_steady *ss);

#endif
