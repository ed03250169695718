/* region.h: mass in a region and the discharge rate fitted to its decline
 * ([DK15] section 4.2: Q from the mass remaining in the silo between 1200
 * and 900 kg). */
#ifndef MPM_DIAG_REGION_H
#define MPM_DIAG_REGION_H

#include <stddef.h>

#include "core/error.h"
#include "core/points.h"

/* Sum of the masses of the points whose centre lies in
 * [xmin, xmax] x [ymin, ymax] [kg/m], in point order. */
double mpm_diag_region_mass(const mpm_points *pts, double xmin, double xmax,
                            double ymin, double ymax);

/* Flow rate Q = -dM/dt [kg/(m s)]: least-squares slope of the samples
 * (t[k], m[k]) with m_lo <= m[k] <= m_hi. *nused (may be NULL) gets their
 * number. MPM_EINVAL when fewer than two samples qualify or they share one
 * time. */
int mpm_diag_region_flow_rate(const double *t, const double *m, size_t n, double m_hi,
                              double m_lo, double *q, size_t *nused, mpm_err *err);

#endif

#include "mesh/mesh.h"

/* Nodal density projected back to the points ([DK15] section 4.3, for the
 * state plot of their Fig. 7): m_i = sum_p N_i(x_p) m_p, V_i = (number of
 * units around node i holding at least one point) V_e / 2^D (the Voronoi
 * cell of the node times the filled fraction of its units), rho_i = m_i / V_i,
 * and rho_p = sum_i N_i(x_p) rho_i with the mesh basis (delta functions).
 * P: points inside mesh m (either dimension); rho: P->n values out.
 * MPM_EOUTSIDE names a point outside the mesh. */
int mpm_diag_nodal_density(const mpm_mesh *m, const mpm_points *P, double *rho, mpm_err *err);
