/* region.c: mass in a region and the flow rate fitted to its decline. */
#include "diag/region.h"

#include <stdlib.h>

double mpm_diag_region_mass(const mpm_points *pts, double xmin, double xmax,
                            double ymin, double ymax)
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
int mpm_diag_region_flow_rate(const double *t, const double *m, size_t n, double m_hi,
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
                       "flow rate: %zu samples with m_lo %g <= mass <= m_hi %g (need 2)", k, m_lo,
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

int mpm_diag_nodal_density(const mpm_mesh *m, size_t n, const double *x, const double *y,
                           const double *mass, double *rho, mpm_err *err)
{
  const size_t nn = (size_t)m->nnodes, nu = (size_t)m->nx * (size_t)m->ny;
  double *mi = calloc(nn, sizeof *mi), *vi = calloc(nn, sizeof *vi);
  unsigned char *filled = calloc(nu, 1);
  int rc = MPM_OK;
  if (!mi || !vi || !filled) {
    rc = mpm_err_set(err, MPM_ENOMEM, "nodal density: out of memory");
    goto done;
  }
  for (size_t p = 0; p < n; p++) {
    int node[4], iu, ju;
    double N[4], gx[4], gy[4];
    int c = mpm_mesh_basis(m, x[p], y[p], node, N, gx, gy);
    if (c < 0 || mpm_mesh_unit(m, x[p], y[p], &iu, &ju) != MPM_OK) {
      rc = mpm_err_set(err, MPM_EOUTSIDE, "nodal density: point %zu at (%.6g, %.6g) m is "
                       "outside the mesh", p, x[p], y[p]);
      goto done;
    }
    filled[(size_t)ju * (size_t)m->nx + (size_t)iu] = 1;
    for (int k = 0; k < c; k++)
      mi[node[k]] += N[k] * mass[p];
  }
  const double quarter = 0.25 * m->dx * m->dy;
  for (int j = 0; j < m->ny; j++)
    for (int i = 0; i < m->nx; i++)
      if (filled[(size_t)j * (size_t)m->nx + (size_t)i]) {
        vi[mpm_mesh_node(m, i, j)] += quarter;
        vi[mpm_mesh_node(m, i + 1, j)] += quarter;
        vi[mpm_mesh_node(m, i, j + 1)] += quarter;
        vi[mpm_mesh_node(m, i + 1, j + 1)] += quarter;
      }
  for (size_t p = 0; p < n; p++) {
    int node[4];
    double N[4], gx[4], gy[4], r = 0.0;
    int c = mpm_mesh_basis(m, x[p], y[p], node, N, gx, gy);
    for (int k = 0; k < c; k++)
      r += N[k] * (vi[node[k]] > 0.0 ? mi[node[k]] / vi[node[k]] : 0.0);
    rho[p] = r;
  }
done:
  free(mi);
  free(vi);
  free(filled);
  return rc;
}
