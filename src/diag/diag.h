/* diag.h: whole-body diagnostics of the point set, one row per output frame.
 *
 * Units are those of the store's dimension: a 2D (plane-strain) store gives
 * values per unit thickness (mass in kg/m, volume in m^2, energy in J/m,
 * momentum in kg/s per m of thickness), a 3D store whole values (kg, m^3,
 * J, kg m/s). The z fields (pz, zcm) are 0 for a 2D store. */
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
  double kinetic;              /* sum m |v|^2 / 2 [J/m; 3D: J] */
  double kinetic_per_mass;     /* kinetic / mass [J/kg] */
  double px, py, pz;           /* momentum [kg/s per m of thickness; 3D: kg m/s] */
  double mass;                 /* [kg/m; 3D: kg] */
  double volume;               /* sum of true volumes [m^2; 3D: m^3] */
  double xcm, ycm, zcm;        /* centre of mass [m] */
  double pmean;                /* mass-weighted mean pressure [Pa] */
  size_t npoints;
  size_t ndisconnected;
  int stop;                    /* enum mpm_stop_reason; set by the caller */
  double mass_removed;         /* mass removed so far [kg/m; 3D: kg]; set by the caller */
  long nremoved;               /* points removed so far; set by the caller */
  double mass_region;          /* mass in the reported region [kg/m; 3D: kg]; set by the caller */
} mpm_diag;

/* Every field but those set by the caller (left 0). */
void mpm_diag_compute(const mpm_points *pts, double t, mpm_diag *d);

/* sum m |v|^2 / 2 / sum m [J/kg] (0 for no mass), in point order: the same
 * value as mpm_diag_compute's kinetic_per_mass, for per-step stop tests. */
double mpm_diag_kinetic_per_mass(const mpm_points *pts);

/* CSV header line and one row of a run of store dimension dim (both end in
 * '\n'). dim 3 appends the columns pz and zcm after the 2D ones, which keep
 * their positions; any other dim gives the 2D columns. The row fails
 * (MPM_EINVAL, buf emptied) when it does not fit in len bytes. */
const char *mpm_diag_csv_header(int dim);
int mpm_diag_csv_row(const mpm_diag *d, int dim, char *buf, size_t len);

#endif
