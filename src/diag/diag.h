/* diag.h: whole-body diagnostics of the point set, one row per output frame. */
#ifndef MPM_DIAG_DIAG_H
#define MPM_DIAG_DIAG_H

#include <stddef.h>

#include "core/points.h"

/* Why a run ended, recorded in the row of its last frame (0 on other rows). */
enum mpm_stop_reason {
  MPM_STOP_NONE = 0,   /* still running */
  MPM_STOP_T_END,      /* reached time.t_end */
  MPM_STOP_KE,         /* kinetic energy per unit mass fell below stop.ke */
  MPM_STOP_MASS,       /* the mass in region fell below stop.mass */
  MPM_STOP_REQUEST     /* stopped on request (a signal) after a checkpoint: resumable */
};

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
  int stop;                    /* enum mpm_stop_reason; set by the caller */
  double mass_removed;         /* mass removed so far [kg/m]; set by the caller */
  long nremoved;               /* points removed so far; set by the caller */
  double mass_region;          /* mass in the reported region [kg/m]; set by the caller */
} mpm_diag;

/* Every field but those set by the caller (left 0). */
void mpm_diag_compute(const mpm_points *pts, double t, mpm_diag *d);

/* sum m |v|^2 / 2 / sum m [J/kg] (0 for no mass), in point order: the same
 * value as mpm_diag_compute's kinetic_per_mass, for per-step stop tests. */
double mpm_diag_kinetic_per_mass(const mpm_points *pts);

/* CSV header line and one row (no trailing newline handling needed: both end in '\n'). */
const char *mpm_diag_csv_header(void);
int mpm_diag_csv_row(const mpm_diag *d, char *buf, size_t len);

#endif
