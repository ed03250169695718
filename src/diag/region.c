/* region.c: mass in a region and the flow rate fitted to its decline. */
#include "diag/region.h"

double mpm_region_mass(const mpm_points *pts, double xmin, double xmax, double ymin,
                       double ymax)
{
  double m = 0.0;
  for (size_t p = 0; p < pts->n; p++)
    if (pts->x[p] >= xmin && pts->x[p] <= xmax && pts->y[p] >= ymin && pts->y[p] <= ymax)
      m += pts->mass[p];
  return m;
}

/* Slope of the least-squares line through the selected samples, from sums
 * about their means (the centred form keeps round-off small when t is large
 * compared with its spread). */
int mpm_region_flow_rate(const double *t, const double *m, size_t n, double m_hi,
                         double m_lo, double *q, size_t *nused, mpm_err *err)
{
  size_t k = 0;
  double st = 0.0, sm = 0.0;
  for (size_t i = 0; i < n; i++)
    if (m[i] >= m_lo && m[i] <= m_hi) {
      st += t[i];
      sm += m[i];
      k++;
    }
  if (nused)
    *nused = k;
  if (k < 2)
    return mpm_err_set(err, MPM_EINVAL,
                       "flow rate: %zu samples with %g <= mass <= %g kg/m (need 2)", k, m_lo,
                       m_hi);
  const double tm = st / (double)k, mm = sm / (double)k;
  double stt = 0.0, stm = 0.0;
  for (size_t i = 0; i < n; i++)
    if (m[i] >= m_lo && m[i] <= m_hi) {
      stt += (t[i] - tm) * (t[i] - tm);
      stm += (t[i] - tm) * (m[i] - mm);
    }
  if (!(stt > 0.0))
    return mpm_err_set(err, MPM_EINVAL, "flow rate: the %zu samples share one time", k);
  *q = -stm / stt;
  return MPM_OK;
}
