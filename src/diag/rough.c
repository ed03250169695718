/* rough.c: roughness of a frame's pressure and its dense fraction (rough.h).
 * Points are linked into square cells of side r over their bounding box; a
 * point's neighbours are looked for in the 3 x 3 cells around its own. */
#include "diag/rough.h"

#include <math.h>
#include <stdlib.h>

/* Median of a[0 .. n-1], n >= 1 (the mean of the two middle values for even
 * n); a is sorted in place (insertion sort: a neighbourhood holds tens of
 * points). */
static double median(double *a, size_t n)
{
  for (size_t i = 1; i < n; i++) {
    const double v = a[i];
    size_t j = i;
    for (; j > 0 && a[j - 1] > v; j--)
      a[j] = a[j - 1];
    a[j] = v;
  }
  return n % 2 ? a[n / 2] : 0.5 * (a[n / 2 - 1] + a[n / 2]);
}

int mpm_diag_roughness(const mpm_points *pts, double r, mpm_roughness *out, mpm_err *err)
{
  *out = (mpm_roughness){.roughness = NAN, .dense_fraction = NAN, .npoints = pts->n};
  if (!(r > 0.0) || !isfinite(r))
    return mpm_err_set(err, MPM_EINVAL, "roughness: radius %g must be > 0", r);
  const size_t n = pts->n;
  if (n == 0)
    return MPM_OK;
  double xlo = INFINITY, ylo = INFINITY, xhi = -INFINITY, yhi = -INFINITY;
  for (size_t p = 0; p < n; p++) {
    xlo = fmin(xlo, pts->x[p]);
    xhi = fmax(xhi, pts->x[p]);
    ylo = fmin(ylo, pts->y[p]);
    yhi = fmax(yhi, pts->y[p]);
    out->ndense += pts->state[p] == MPM_STATE_DENSE;
  }
  out->dense_fraction = (double)out->ndense / (double)n;
  const double cx = floor((xhi - xlo) / r) + 1.0, cy = floor((yhi - ylo) / r) + 1.0;
  if (!(cx * cy < 1e8))
    return mpm_err_set(err, MPM_EINVAL, "roughness: radius %g too small for the %g x %g m frame",
                       r, xhi - xlo, yhi - ylo);
  const long nx = (long)cx, ny = (long)cy;
  long *head = malloc((size_t)(nx * ny) * sizeof *head), *next = malloc(n * sizeof *next);
  double *p = malloc(n * sizeof *p), *buf = malloc(n * sizeof *buf);
  if (!head || !next || !p || !buf) {
    free(head);
    free(next);
    free(p);
    free(buf);
    return mpm_err_set(err, MPM_ENOMEM, "roughness: no memory for %zu points", n);
  }
  for (long c = 0; c < nx * ny; c++)
    head[c] = -1;
  for (size_t q = n; q-- > 0;) {          /* dense points only, linked per cell */
    p[q] = mpm_points_pressure(pts, q);
    if (pts->state[q] != MPM_STATE_DENSE)
      continue;
    const long c = (long)((pts->x[q] - xlo) / r) + nx * (long)((pts->y[q] - ylo) / r);
    next[q] = head[c];
    head[c] = (long)q;
  }
  double dev = 0.0, sum_p = 0.0;
  const double r2 = r * r;
  for (size_t q = 0; q < n; q++) {
    if (pts->state[q] != MPM_STATE_DENSE)
      continue;
    const long i = (long)((pts->x[q] - xlo) / r), j = (long)((pts->y[q] - ylo) / r);
    size_t m = 0;
    for (long b = j - 1; b <= j + 1; b++)
      for (long a = i - 1; a <= i + 1; a++) {
        if (a < 0 || a >= nx || b < 0 || b >= ny)
          continue;
        for (long o = head[a + nx * b]; o >= 0; o = next[o]) {
          const double ex = pts->x[o] - pts->x[q], ey = pts->y[o] - pts->y[q];
          if ((size_t)o != q && ex * ex + ey * ey <= r2)
            buf[m++] = p[o];
        }
      }
    if (m == 0)
      continue;
    dev += fabs(p[q] - median(buf, m));  /* |p_i - median of its neighbours| */
    sum_p += p[q];
    out->nused++;
  }
  if (out->nused > 0) {
    out->mean_p = sum_p / (double)out->nused;
    out->roughness = (dev / (double)out->nused) / out->mean_p;
  }
  free(head);
  free(next);
  free(p);
  free(buf);
  return MPM_OK;
}
