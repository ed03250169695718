/* rough.h: how clean the stress field of one frame is (docs/diagnostics.md,
 * "Roughness").
 *
 * Over the dense points i (state dense) that have at least one other dense
 * point within the distance r:
 *   roughness = mean_i |p_i - median_j p_j| / mean_i p_i,
 * the median over those neighbours j != i; and the dense fraction, dense
 * points over all points. A smooth pressure field (lithostatic, linear in
 * space) gives a roughness of order (r/H)^2 at most, where H is its scale of
 * variation; a pattern alternating from point to point gives its full
 * relative amplitude (twice it for +-a about the mean). Points are binned in
 * square cells of side r, so the cost is linear in the point count. */
#ifndef MPM_DIAG_ROUGH_H
#define MPM_DIAG_ROUGH_H

#include <stddef.h>

#include "core/error.h"
#include "core/points.h"

typedef struct mpm_roughness {
  double roughness;       /* mean |p - median of neighbours| / mean p (NaN if no point counts) */
  double dense_fraction;  /* dense points / points (NaN without points) */
  double mean_p;          /* mean pressure of the points that count [Pa] */
  size_t npoints, ndense; /* points, dense points */
  size_t nused;           /* dense points with a dense neighbour within r */
} mpm_roughness;

/* The roughness of the frame's pressure within radius r > 0 (MPM_EINVAL
 * otherwise, or MPM_ENOMEM). */
int mpm_diag_roughness(const mpm_points *pts, double r, mpm_roughness *out, mpm_err *err);

#endif
