/* jam.h: is a silo jammed? The classifier of [DK-silo] section 7.2.
 *
 * From the frames of a run: the mass-weighted mean vertical velocity of the
 * dense material vbar(t), and the number of points that left the domain
 * between consecutive frames. vbar is the velocity the material moved with
 * from one frame to the next: the mean of (y_k - y_{k-1}) / (t_k - t_{k-1})
 * over the points dense in both frames (matched by id). The points' own
 * velocities would not do: under FLIP a point pressed against a wall can
 * carry a velocity the grid never moves it with (on the jamming silo,
 * points at the feet of a static arch keep 0.07 - 0.2 m/s upwards while they
 * stay where they are, enough to hold the mean of the whole silo above 0).
 * Two votes:
 *
 *  - velocity: the last zero crossing of vbar (a sign change between two
 *    frames, at the time interpolated linearly between them; frames with
 *    vbar exactly 0 or without dense material are skipped) lies in the last
 *    tenth of the run: static; before half of it, or there is none: flowing;
 *    in between: unsure;
 *  - outflow: the mean number of points leaving per frame over the frames of
 *    the last tenth of the run (t >= 0.9 t_end): <= 1 static, > 10 flowing,
 *    in between unsure.
 *
 * The class is static or flowing when both votes say so, unsure otherwise.
 * The thresholds are the paper's. */
#ifndef MPM_DIAG_JAM_H
#define MPM_DIAG_JAM_H

#include <stddef.h>

#include "core/error.h"
#include "core/points.h"

enum mpm_jam_class { MPM_JAM_UNSURE = 0, MPM_JAM_STATIC, MPM_JAM_FLOWING };

typedef struct mpm_jam {
  int cls;              /* enum mpm_jam_class */
  double t_end;         /* time of the last frame [s] */
  double t_zero;        /* last zero crossing of vbar [s]; NaN: none */
  int v_vote;           /* enum mpm_jam_class of the velocity test */
  double leaving;       /* mean points leaving per frame over the last tenth */
  int n_vote;           /* enum mpm_jam_class of the outflow test */
  int frames;           /* frames in the last tenth */
} mpm_jam;

/* Mass-weighted mean of (y - y_prev) / dt over the points of now that are
 * dense there and in prev, matched by id; NaN when there are none or dt is
 * not > 0. slot: nslot ints, all -1 on entry and again on return, nslot
 * above every id of prev (ids of prev beyond it are not matched). Vertical
 * displacements across a periodic y edge are not unwrapped. */
double mpm_diag_dense_vy_moved(const mpm_points *prev, const mpm_points *now, double dt, int *slot,
                               size_t nslot);

/* Classify nf >= 2 frames at increasing times t[k] (t[0] the start), with
 * vbar[k] as from mpm_diag_dense_vy_moved (NaN for the first frame) and
 * npoints[k] the points in the domain (points only ever leave). Fewer than
 * two frames, times not increasing or a point count that grows: MPM_EINVAL. */
int mpm_diag_jam(size_t nf, const double *t, const double *vbar, const size_t *npoints,
                 mpm_jam *out, mpm_err *err);

/* "unsure", "static", "flowing". */
const char *mpm_diag_jam_name(int cls);

#endif
