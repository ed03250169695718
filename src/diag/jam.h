/* jam.h: is a silo jammed? The classifier of [DK-silo] section 7.2.
 *
 * From the frames of a run: the mass-weighted mean vertical velocity of the
 * dense material vbar(t), and the number of points that left the domain
 * between consecutive frames. Two votes:
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

/* Mass-weighted mean vy of the dense points of a frame; NaN when none. */
double mpm_diag_dense_vy(const mpm_points *pts);

/* Classify nf >= 2 frames at increasing times t[k] (t[0] the start), with
 * vbar[k] as from mpm_diag_dense_vy and npoints[k] the points in the domain
 * (points only ever leave). Fewer than two frames, times not increasing or
 * a point count that grows: MPM_EINVAL. */
int mpm_diag_jam(size_t nf, const double *t, const double *vbar, const size_t *npoints,
                 mpm_jam *out, mpm_err *err);

/* "unsure", "static", "flowing". */
const char *mpm_diag_jam_name(int cls);

#endif
