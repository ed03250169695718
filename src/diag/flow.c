/* flow.c: diagnostics of one frame of a flow ([DK15] sections 4.1, 4.4).
 *
 *   profile   vx(bin) = sum_bin m vx / sum_bin m
 *   layer     vbar = sum m vx / sum m,  mu = sum m tau / sum m p (flowing layer),
 *             tau = sqrt(s0:s0 / 2), p = -tr(sigma)/3 (MODEL.md section 1)
 *   front     largest x of a point with >= min_count points in its 3x3 cells
 *   surface   largest y per column; slope by least squares; the sloping part
 *             from 90% to 10% of the highest top
 *   smoothing [DK15] eqs. 4.1-4.3 with the run's S_ip
 *
 * Sums run serially in point order. Nothing here prints. */
#include "diag/flow.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

int mpm_diag_profile(const mpm_points *pts, double ymin, double ymax, int nbins,
                     mpm_profile_bin *bins, mpm_err *err)
{
  if (!pts || !bins || nbins < 1)
    return mpm_err_set(err, MPM_EINVAL, "profile: need points and nbins >= 1 (got %d)", nbins);
  if (!(ymax > ymin) || !isfinite(ymin) || !isfinite(ymax))
    return mpm_err_set(err, MPM_EINVAL, "profile: range [%g, %g] is empty", ymin, ymax);
  const double h = (ymax - ymin) / nbins;
  double *mvx = calloc((size_t)nbins, sizeof *mvx), *mvy = calloc((size_t)nbins, sizeof *mvy);
  if (!mvx || !mvy) {
    free(mvx);
    free(mvy);
    return mpm_err_set(err, MPM_ENOMEM, "profile: out of memory");
  }
  for (int k = 0; k < nbins; k++) {
    bins[k] = (mpm_profile_bin){.y = (k + 0.5) * h};
  }
  for (size_t i = 0; i < pts->n; i++) {
    double y = pts->y[i];
    if (!(y >= ymin && y <= ymax))
      continue;
    int k = (int)((y - ymin) / h);
    if (k >= nbins)
      k = nbins - 1;                       /* y = ymax */
    double m = pts->mass[i];
    bins[k].mass += m;
    bins[k].n++;
    mvx[k] += m * pts->vx[i];
    mvy[k] += m * pts->vy[i];
  }
  for (int k = 0; k < nbins; k++)
    if (bins[k].mass > 0.0) {
      bins[k].vx = mvx[k] / bins[k].mass;
      bins[k].vy = mvy[k] / bins[k].mass;
    }
  free(mvx);
  free(mvy);
  return MPM_OK;
}

/* tau = sqrt(s0:s0 / 2) of the in-plane stress (xx, yy, zz, xy). */
static double shear_invariant(double sxx, double syy, double szz, double sxy, double p)
{
  double a = sxx + p, b = syy + p, c = szz + p;
  return sqrt(0.5 * (a * a + b * b + c * c + 2.0 * sxy * sxy));
}

void mpm_diag_flow(const mpm_points *pts, double gdot_min, mpm_flow *f)
{
  double m = 0, mvx = 0, msp = 0, mtau = 0, mp = 0, fm = 0, ymax = -INFINITY;
  memset(f, 0, sizeof *f);
  if (!pts || pts->n == 0)
    return;
  for (size_t i = 0; i < pts->n; i++) {
    double mi = pts->mass[i], vx = pts->vx[i], vy = pts->vy[i];
    m += mi;
    mvx += mi * vx;
    msp += mi * hypot(vx, vy);
    if (pts->y[i] > ymax)
      ymax = pts->y[i];
    double p = mpm_points_pressure(pts, i);
    if (pts->state[i] != MPM_STATE_DENSE || !(p > 0.0) || pts->gdp[i] < gdot_min)
      continue;
    fm += mi;
    mp += mi * p;
    mtau += mi * shear_invariant(pts->sxx[i], pts->syy[i], pts->szz[i], pts->sxy[i], p);
  }
  f->mass = m;
  f->flow_mass = fm;
  f->ymax = ymax;
  if (m > 0.0) {
    f->vx = mvx / m;
    f->speed = msp / m;
  }
  if (mp > 0.0)
    f->mu = mtau / mp;
}

/* ---- front ----------------------------------------------------------------- */

int mpm_diag_front(const mpm_points *pts, double h, int min_count, double *xfront,
                   mpm_err *err)
{
  if (!pts || pts->n == 0)
    return mpm_err_set(err, MPM_EINVAL, "front: no points");
  double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
  for (size_t i = 0; i < pts->n; i++) {
    xmin = fmin(xmin, pts->x[i]);
    xmax = fmax(xmax, pts->x[i]);
    ymin = fmin(ymin, pts->y[i]);
    ymax = fmax(ymax, pts->y[i]);
  }
  if (min_count <= 1) {
    *xfront = xmax;
    return MPM_OK;
  }
  if (!(h > 0.0))
    return mpm_err_set(err, MPM_EINVAL, "front: cell size %g must be > 0", h);
  double nxd = floor((xmax - xmin) / h) + 1.0, nyd = floor((ymax - ymin) / h) + 1.0;
  if (nxd * nyd > 1e8)
    return mpm_err_set(err, MPM_EINVAL, "front: cell size %g too small for a %g x %g m set",
                       h, xmax - xmin, ymax - ymin);
  const long nx = (long)nxd, ny = (long)nyd;
  int *count = calloc((size_t)(nx * ny), sizeof *count);
  if (!count)
    return mpm_err_set(err, MPM_ENOMEM, "front: out of memory");
  for (size_t i = 0; i < pts->n; i++) {
    long cx = (long)((pts->x[i] - xmin) / h), cy = (long)((pts->y[i] - ymin) / h);
    count[(cx < nx ? cx : nx - 1) + nx * (cy < ny ? cy : ny - 1)]++;
  }
  double best = -INFINITY;
  for (size_t i = 0; i < pts->n; i++) {
    if (pts->x[i] <= best)
      continue;
    long cx = (long)((pts->x[i] - xmin) / h), cy = (long)((pts->y[i] - ymin) / h);
    cx = cx < nx ? cx : nx - 1;
    cy = cy < ny ? cy : ny - 1;
    int c = 0;
    for (long j = cy - 1; j <= cy + 1; j++)
      for (long k = cx - 1; k <= cx + 1; k++)
        if (j >= 0 && j < ny && k >= 0 && k < nx)
          c += count[k + nx * j];
    if (c >= min_count)
      best = pts->x[i];
  }
  free(count);
  if (best == -INFINITY)
    return mpm_err_set(err, MPM_EINVAL, "front: every point is isolated (cells %g m, "
                       "at least %d points)", h, min_count);
  *xfront = best;
  return MPM_OK;
}

/* ---- free surface ---------------------------------------------------------- */

int mpm_diag_surface(const mpm_points *pts, double x0, double w, int ncol, double *top,
                     mpm_err *err)
{
  if (!pts || !top || ncol < 1 || !(w > 0.0))
    return mpm_err_set(err, MPM_EINVAL, "surface: need ncol >= 1 (got %d) and width > 0 "
                       "(got %g)", ncol, w);
  for (int k = 0; k < ncol; k++)
    top[k] = NAN;
  for (size_t i = 0; i < pts->n; i++) {
    double u = (pts->x[i] - x0) / w;
    if (!(u >= 0.0 && u < ncol))
      continue;
    int k = (int)u;
    if (isnan(top[k]) || pts->y[i] > top[k])
      top[k] = pts->y[i];
  }
  return MPM_OK;
}

int mpm_diag_slope_range(const mpm_points *pts, double x0, double w, int ncol, double ybase,
                         double *xa, double *xb, mpm_err *err)
{
  if (ncol < 1)
    return mpm_err_set(err, MPM_EINVAL, "slope range: need ncol >= 1 (got %d)", ncol);
  double *top = malloc((size_t)ncol * sizeof *top), hmax = -INFINITY;
  int ka = -1, kb = -1;
  if (!top)
    return mpm_err_set(err, MPM_ENOMEM, "slope range: out of memory");
  int rc = mpm_diag_surface(pts, x0, w, ncol, top, err);
  for (int k = 0; rc == MPM_OK && k < ncol; k++)
    if (!isnan(top[k]) && top[k] - ybase > hmax)
      hmax = top[k] - ybase;
  for (int k = 0; rc == MPM_OK && k < ncol; k++) {
    if (isnan(top[k]))
      continue;
    if (ka < 0 && top[k] - ybase < 0.9 * hmax)
      ka = k;
    if (top[k] - ybase > 0.1 * hmax)
      kb = k;
  }
  free(top);
  if (rc == MPM_OK && (ka < 0 || kb < ka + 1))
    rc = mpm_err_set(err, MPM_EINVAL, "slope auto: no sloping part of the surface found");
  if (rc == MPM_OK) {
    *xa = x0 + ka * w;
    *xb = x0 + (kb + 1) * w;
  }
  return rc;
}

/* Centred sums keep the fit accurate far from the origin. */
int mpm_diag_line_fit(size_t n, const double *x, const double *y, double *a, double *b,
                      mpm_err *err)
{
  double sx = 0, sy = 0;
  size_t m = 0;
  for (size_t i = 0; i < n; i++)
    if (isfinite(y[i]) && isfinite(x[i])) {
      sx += x[i];
      sy += y[i];
      m++;
    }
  if (m < 2)
    return mpm_err_set(err, MPM_EINVAL, "line fit: %zu usable pair(s), need 2", m);
  double xm = sx / (double)m, ym = sy / (double)m, sxx = 0, sxy = 0;
  for (size_t i = 0; i < n; i++)
    if (isfinite(y[i]) && isfinite(x[i])) {
      sxx += (x[i] - xm) * (x[i] - xm);
      sxy += (x[i] - xm) * (y[i] - ym);
    }
  if (!(sxx > 0.0))
    return mpm_err_set(err, MPM_EINVAL, "line fit: all x are equal");
  *b = sxy / sxx;
  *a = ym - *b * xm;
  return MPM_OK;
}

int mpm_diag_heap_slope(const mpm_points *pts, double xa, double xb, double w, double *slope,
                        mpm_err *err)
{
  if (!(xb > xa) || !(w > 0.0))
    return mpm_err_set(err, MPM_EINVAL, "heap slope: need xa < xb and w > 0 (got %g, %g, %g)",
                       xa, xb, w);
  double nd = floor((xb - xa) / w);
  if (nd < 2 || nd > 1e7)
    return mpm_err_set(err, MPM_EINVAL, "heap slope: %g columns of %g m in [%g, %g], need 2 to 1e7",
                       nd, w, xa, xb);
  int n = (int)nd;
  double *top = malloc(2 * (size_t)n * sizeof *top);
  if (!top)
    return mpm_err_set(err, MPM_ENOMEM, "heap slope: out of memory");
  double *xc = top + n, a;
  int rc = mpm_diag_surface(pts, xa, w, n, top, err);
  for (int k = 0; k < n; k++)
    xc[k] = xa + (k + 0.5) * w;
  if (rc == MPM_OK)
    rc = mpm_diag_line_fit((size_t)n, xc, top, &a, slope, err);
  free(top);
  return rc;
}

/* ---- point values ------------------------------------------------------------ */

void mpm_diag_pressure(const mpm_points *pts, double *p)
{
  for (size_t i = 0; i < pts->n; i++)
    p[i] = mpm_points_pressure(pts, i);
}

/* ---- time series ----------------------------------------------------------- */

int mpm_diag_derivative(size_t n, const double *t, const double *v, double *dvdt,
                        mpm_err *err)
{
  if (n < 2)
    return mpm_err_set(err, MPM_EINVAL, "derivative: %zu sample(s), need 2", n);
  for (size_t i = 1; i < n; i++)
    if (!(t[i] > t[i - 1]))
      return mpm_err_set(err, MPM_EINVAL, "derivative: times not increasing at sample %zu", i);
  dvdt[0] = (v[1] - v[0]) / (t[1] - t[0]);
  dvdt[n - 1] = (v[n - 1] - v[n - 2]) / (t[n - 1] - t[n - 2]);
  for (size_t i = 1; i + 1 < n; i++) {
    /* v'(t_i) of the parabola through three samples, h1 = t_i - t_{i-1}, h2 = t_{i+1} - t_i */
    double h1 = t[i] - t[i - 1], h2 = t[i + 1] - t[i];
    dvdt[i] = (h1 * h1 * (v[i + 1] - v[i]) + h2 * h2 * (v[i] - v[i - 1])) / (h1 * h2 * (h1 + h2));
  }
  return MPM_OK;
}

/* ---- nodal smoothing ------------------------------------------------------- */

int mpm_diag_smooth(const mpm_shape_stencil *st, size_t n, const double *mass, const double *f,
                    int nnodes, double *nm, double *nmf, double *out, mpm_err *err)
{
  if (!st || n > st->cap || nnodes < 1)
    return mpm_err_set(err, MPM_EINVAL, "smooth: stencil too small or no nodes");
  memset(nm, 0, (size_t)nnodes * sizeof *nm);
  memset(nmf, 0, (size_t)nnodes * sizeof *nmf);
  for (size_t p = 0; p < n; p++)
    for (int k = 0; k < st->count[p]; k++) {
      int i = st->node[p * (size_t)st->w + k];
      double Sm = st->S[p * (size_t)st->w + k] * mass[p];
      if (i < 0 || i >= nnodes)
        return mpm_err_set(err, MPM_EINVAL, "smooth: node %d of point %zu outside 0..%d", i,
                           p, nnodes - 1);
      nm[i] += Sm;                         /* m_i = sum S_ip m_p */
      nmf[i] += Sm * f[p];                 /* (m f)_i = sum S_ip m_p f_p  (4.1) */
    }
  for (int i = 0; i < nnodes; i++)
    nmf[i] = nm[i] > 0.0 ? nmf[i] / nm[i] : 0.0;   /* f_i = (m f)_i / m_i  (4.2) */
  for (size_t p = 0; p < n; p++) {
    double s = 0.0;
    for (int k = 0; k < st->count[p]; k++)
      s += st->S[p * (size_t)st->w + k] * nmf[st->node[p * (size_t)st->w + k]];
    out[p] = s;                            /* out_p = sum S_ip f_i  (4.3) */
  }
  return MPM_OK;
}
