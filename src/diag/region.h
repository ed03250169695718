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
double mpm_region_mass(const mpm_points *pts, double xmin, double xmax, double ymin,
                       double ymax);

/* Flow rate Q = -dM/dt [kg/(m s)]: least-squares slope of the samples
 * (t[k], m[k]) with m_lo <= m[k] <= m_hi. *nused (may be NULL) gets their
 * number. MPM_EINVAL when fewer than two samples qualify or they share one
 * time. */
int mpm_region_flow_rate(const double *t, const double *m, size_t n, double m_hi,
                         double m_lo, double *q, size_t *nused, mpm_err *err);

#endif
