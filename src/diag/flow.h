/* flow.h: diagnostics of one frame of a flow ([DK15] sections 4.1 and 4.4).
 *
 * Velocity profile across the depth, depth-averaged speed, mean mu of the
 * flowing layer, front position (run-out), free-surface slope of a heap and
 * the range of it that slopes, the point pressures, the
 * time derivative of a sampled series (depth-averaged acceleration) and the
 * nodal smoothing of point values for plots ([DK15] eqs. 4.1-4.3). All sums
 * run serially in point order. Coordinates are those of the mesh: for an
 * incline (gravity.angle) x runs down the slope and y is the height above the
 * base. docs/diagnostics.md gives the definitions. */
#ifndef MPM_DIAG_FLOW_H
#define MPM_DIAG_FLOW_H

#include <stddef.h>

#include "core/error.h"
#include "core/points.h"
#include "shape/shape.h"

/* One bin of a depth profile. */
typedef struct mpm_profile_bin {
  double y;     /* bin centre, height above ymin [m] */
  double vx;    /* mass-weighted mean velocity along x [m/s] (0 if empty) */
  double vy;    /* mass-weighted mean velocity along y [m/s] (0 if empty) */
  double mass;  /* mass in the bin [kg/m] */
  size_t n;     /* points in the bin */
} mpm_profile_bin;

/* Velocity profile: nbins equal bins over [ymin, ymax]; a point at height y
 * belongs to bin floor((y - ymin) / (ymax - ymin) * nbins) (y = ymax to the
 * last bin); points outside [ymin, ymax] are left out. */
int mpm_diag_profile(const mpm_points *pts, double ymin, double ymax, int nbins,
                     mpm_profile_bin *bins, mpm_err *err);

/* Means over the layer. */
typedef struct mpm_flow {
  double mass;        /* total mass [kg/m] */
  double vx;          /* sum m vx / sum m: depth-averaged speed along x on an
                       * incline of uniform density [m/s] */
  double speed;       /* sum m |v| / sum m [m/s] */
  double mu;          /* sum m tau / sum m p over the flowing layer: dense points
                       * with p > 0 and gdot_p >= gdot_min (0 if none) */
  double flow_mass;   /* mass of the flowing layer [kg/m] */
  double ymax;        /* largest y of any point [m] */
} mpm_flow;

void mpm_diag_flow(const mpm_points *pts, double gdot_min, mpm_flow *f);

/* Front (run-out) position: the largest x among points that are not
 * isolated. Points are binned into square cells of side h from the smallest
 * x and y; a point is isolated when the 3 x 3 cells around its own hold fewer
 * than min_count points, itself included. min_count <= 1 gives the plain
 * largest x. Empty point set: MPM_EINVAL. */
int mpm_diag_front(const mpm_points *pts, double h, int min_count, double *xfront,
                   mpm_err *err);

/* Free surface: top[k] = largest y of the points with x in column
 * [x0 + k w, x0 + (k+1) w), k < ncol; NaN for an empty column. */
int mpm_diag_surface(const mpm_points *pts, double x0, double w, int ncol, double *top,
                     mpm_err *err);

/* The part of a heap's free surface that slopes ("--slope auto",
 * docs/diagnostics.md): with the surface in ncol columns of width w from x0
 * (mpm_diag_surface) and heights h = top - ybase, *xa is the left edge of the
 * first column, left to right, with h < 0.9 hmax and *xb the right edge of
 * the last column with h > 0.1 hmax, hmax the largest h; empty columns are
 * skipped. MPM_EINVAL when no column is below 0.9 hmax or none above
 * 0.1 hmax lies to the right of the first one that is. */
int mpm_diag_slope_range(const mpm_points *pts, double x0, double w, int ncol, double ybase,
                         double *xa, double *xb, mpm_err *err);

/* Least-squares line y = a + b x through the pairs with finite y; at least
 * two distinct x needed (else MPM_EINVAL). */
int mpm_diag_line_fit(size_t n, const double *x, const double *y, double *a, double *b,
                      mpm_err *err);

/* Free-surface slope of a heap over [xa, xb]: the surface in columns of width
 * w (mpm_diag_surface), fitted by a line; *slope = dy/dx of the fit. */
int mpm_diag_heap_slope(const mpm_points *pts, double xa, double xb, double w, double *slope,
                        mpm_err *err);

/* Derivative of a series v(t) (n >= 2, t strictly increasing): three-point
 * formula for unequal spacing inside (exact for quadratics), one-sided
 * differences at the ends. */
int mpm_diag_derivative(size_t n, const double *t, const double *v, double *dvdt,
                        mpm_err *err);

/* Pressure of every point, p[i] = -(sxx + syy + szz) / 3 (n values). */
void mpm_diag_pressure(const mpm_points *pts, double *p);

/* Nodal smoothing of a point field f for plots ([DK15] eqs. 4.1-4.3):
 *   (m f)_i = sum_p S_ip m_p f_p,  f_i = (m f)_i / m_i,  out_p = sum_i S_ip f_i,
 * with the stencil st of the n points and nodal workspace nm, nmf of nnodes
 * entries. Nodes with m_i <= 0 do not contribute. */
int mpm_diag_smooth(const mpm_shape_stencil *st, size_t n, const double *mass, const double *f,
                    int nnodes, double *nm, double *nmf, double *out, mpm_err *err);

#endif
