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

int mpm_diag_nodal_density(const mpm_mesh *m, const mpm_points *P, double *rho, mpm_err *err)
{
  const size_t n = P->n, nn = (size_t)m->nnodes, nu = m->nunits;
  const int D = m->dim;
  double *mi = calloc(nn, sizeof *mi), *vi = calloc(nn, sizeof *vi);
  unsigned char *filled = calloc(nu, 1);
  int rc = MPM_OK;
  if (!mi || !vi || !filled) {
    rc = mpm_err_set(err, MPM_ENOMEM, "nodal density: out of memory");
    goto done;
  }
  int node[8], u[3];
  double N[8], g[3][8];
  double *const dN[3] = {g[0], g[1], g[2]};
  for (size_t p = 0; p < n; p++) {
    const double x[3] = {P->x[p], P->y[p], D == 3 ? P->z[p] : 0.0};
    int c = mpm_mesh_basis(m, x, node, N, dN);
    if (c < 0 || mpm_mesh_unit(m, x, u) != MPM_OK) {
      rc = mpm_err_set(err, MPM_EOUTSIDE, "nodal density: point %d at (%.6g, %.6g) m is "
                       "outside the mesh", P->id[p], x[0], x[1]);
      goto done;
    }
    filled[mpm_mesh_unit_index(m, u)] = 1;
    for (int k = 0; k < c; k++)
      mi[node[k]] += N[k] * P->mass[p];
  }
  const double share = D == 3 ? 0.125 * m->dx * m->dy * m->dz : 0.25 * m->dx * m->dy;  /* V_e / 2^D */
  for (u[2] = 0; u[2] < m->nz; u[2]++)
    for (u[1] = 0; u[1] < m->ny; u[1]++)
      for (u[0] = 0; u[0] < m->nx; u[0]++)
        if (filled[mpm_mesh_unit_index(m, u)]) {
          int id[8];
          mpm_mesh_unit_corners(m, u, id);
          for (int a = 0; a < 1 << D; a++)
            vi[id[a]] += share;
        }
  for (size_t p = 0; p < n; p++) {
    const double x[3] = {P->x[p], P->y[p], D == 3 ? P->z[p] : 0.0};
    double r = 0.0;
    int c = mpm_mesh_basis(m, x, node, N, dN);
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
