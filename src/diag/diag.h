/* diag.h: whole-body diagnostics of the point set, one row per output frame. */
#ifndef MPM_DIAG_DIAG_H
#define MPM_DIAG_DIAG_H

#include <stddef.h>

#include "core/points.h"

typedef struct mpm_diag {
  double t;                    /* time [s] */
  double kinetic;              /* sum m |v|^2 / 2 [J/m] */
  double kinetic_per_mass;     /* kinetic / mass [J/kg] */
  double px, py;               /* momentum [kg/s] (per unit thickness) */
  double mass;                 /* [kg/m] */
  double volume;               /* sum of true volumes [m^2] */
  double xcm, ycm;             /* centre of mass [m] */
  double pmean;                /* mass-weighted mean pressure [Pa] */
  size_t npoints;
  size_t ndisconnected;
} mpm_diag;

void mpm_diag_compute(const mpm_points *pts, double t, mpm_diag *d);

/* CSV header line and one row (no trailing newline handling needed: both end in '\n'). */
const char *mpm_diag_csv_header(void);
int mpm_diag_csv_row(const mpm_diag *d, char *buf, size_t len);

#endif
