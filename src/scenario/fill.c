/* fill.c: fill regions with material points (initial state).
 *
 * Points sit at the centres of an n x n sub-grid of every mesh unit whose
 * sub-cell centre lies in the region: V_p = dx dy / n^2, m_p = rho V_p,
 * uGIMP extent r1 = (dx/2n, 0), r2 = (0, dy/2n). A lithostatic pre-stress sets
 * sigma_yy = rho g_y (y_top - y) with y_top the top of the fill above the point
 * and sigma_xx = sigma_zz = K0 sigma_yy, K0 = nu / (1 - nu) (uniaxial strain).
 * An isotropic pre-stress (`pressure`) sets sigma = -p I ([D-thesis] ch. 4:
 * "initially isotropically compressed").
 * The pre-stressed material is compressed consistently with the hypoelastic
 * law dp = K drho / rho: rho = rho_fill exp(p / K), so the mass grows. */
#include "scenario/scenario.h"

#include <math.h>
#include <stdlib.h>

/* Even-odd rule: a ray to +x crosses the polygon boundary an odd number of times. */
static int inside_polygon(const mpm_fill_config *f, double x, double y)
{
  int in = 0;
  for (int a = 0, b = f->nvert - 1; a < f->nvert; b = a++) {
    double ya = f->py[a], yb = f->py[b];
    if ((ya > y) != (yb > y)) {
      double xc = f->px[a] + (y - ya) * (f->px[b] - f->px[a]) / (yb - ya);
      if (x < xc)
        in = !in;
    }
  }
  return in;
}

int mpm_scenario_inside(const mpm_fill_config *f, double x, double y)
{
  switch (f->shape) {
  case MPM_FILL_RECTANGLE:
    return x >= f->xmin && x <= f->xmax && y >= f->ymin && y <= f->ymax;
  case MPM_FILL_DISC: {
    double ex = x - f->cx, ey = y - f->cy;
    return ex * ex + ey * ey <= f->radius * f->radius;
  }
  case MPM_FILL_POLYGON:
    return inside_polygon(f, x, y);
  default:
    return 0;
  }
}

/* sigma_yy = rho gy (y_top - y) for every point appended since `first`; y_top is
 * the highest point of the same sub-column plus half a sub-cell. */
static int lithostatic(mpm_points *pts, size_t first, const mpm_mesh *m, int n,
                       const mpm_fill_config *f, const mpm_material_params *par, double gy)
{
  size_t ncol = (size_t)m->nx * (size_t)n;
  double *ytop = malloc(ncol * sizeof *ytop);
  if (!ytop)
    return MPM_ENOMEM;
  double hx = m->dx / n, hy = m->dy / n;
  for (size_t c = 0; c < ncol; c++)
    ytop[c] = -INFINITY;
  for (size_t p = first; p < pts->n; p++) {
    size_t c = (size_t)floor((pts->x[p] - m->x0) / hx);
    if (pts->y[p] > ytop[c]) ytop[c] = pts->y[p];
  }
  double k0 = par->nu / (1.0 - par->nu);                    /* K0 = nu / (1 - nu) */
  for (size_t p = first; p < pts->n; p++) {
    size_t c = (size_t)floor((pts->x[p] - m->x0) / hx);
    double syy = f->density * gy * (ytop[c] + 0.5 * hy - pts->y[p]);  /* gy < 0: compression */
    pts->syy[p] = syy;
    pts->sxx[p] = pts->szz[p] = k0 * syy;
    double pr = -(1.0 + 2.0 * k0) * syy / 3.0;               /* p = -tr(sigma)/3 */
    pts->mass[p] *= exp(pr / par->K);                         /* rho = rho_fill exp(p/K) */
  }
  free(ytop);
  return MPM_OK;
}

int mpm_scenario_fill(mpm_points *pts, const mpm_mesh *m, const mpm_fill_config *f,
                      const mpm_material_params *par, double gy, mpm_err *err)
{
  int n = f->ppu;
  if (n < 1)
    return mpm_err_set(err, MPM_EINPUT, "fill: ppu = %d must be >= 1", n);
  if (!(f->density > 0.0))
    return mpm_err_set(err, MPM_EINPUT, "fill: density = %g must be > 0 kg/m^3", f->density);
  double hx = m->dx / n, hy = m->dy / n;
  double vol = hx * hy;                                    /* V_p = dx dy / n^2 */
  int state = (par->rho_c > 0.0 && f->density < par->rho_c) ? MPM_STATE_DISCONNECTED
                                                             : MPM_STATE_DENSE;
  size_t first = pts->n, count = 0;
  for (int j = 0; j < m->ny * n; j++)             /* room for exactly the points to come */
    for (int i = 0; i < m->nx * n; i++)
      count += mpm_scenario_inside(f, m->x0 + (i + 0.5) * hx, m->y0 + (j + 0.5) * hy) != 0;
  if (mpm_points_reserve(pts, pts->n + count) != MPM_OK)
    return mpm_err_set(err, MPM_ENOMEM, "fill: out of memory for %zu points", pts->n + count);
  for (int j = 0; j < m->ny * n; j++) {
    double y = m->y0 + (j + 0.5) * hy;
    for (int i = 0; i < m->nx * n; i++) {
      double x = m->x0 + (i + 0.5) * hx;
      if (!mpm_scenario_inside(f, x, y))
        continue;
      size_t p;
      if (mpm_points_push(pts, &p) != MPM_OK)
        return mpm_err_set(err, MPM_ENOMEM, "fill: out of memory at %zu points", pts->n);
      pts->x[p] = x;
      pts->y[p] = y;
      pts->vx[p] = f->vx;
      pts->vy[p] = f->vy;
      pts->vol[p] = vol;
      pts->mass[p] = f->density * vol;                     /* m_p = rho V_p */
      pts->r1x[p] = 0.5 * hx;
      pts->r2y[p] = 0.5 * hy;
      pts->state[p] = state;
    }
  }
  if (pts->n == first)
    return mpm_err_set(err, MPM_EINPUT, "fill: region contains no point centre at ppu = %d", n);
  if (f->lithostatic && lithostatic(pts, first, m, n, f, par, gy) != MPM_OK)
    return mpm_err_set(err, MPM_ENOMEM, "fill: out of memory");
  if (f->pressure > 0.0)
    for (size_t p = first; p < pts->n; p++) {               /* sigma = -p I */
      pts->sxx[p] = pts->syy[p] = pts->szz[p] = -f->pressure;
      pts->mass[p] *= exp(f->pressure / par->K);            /* rho = rho_fill exp(p/K) */
    }
  return MPM_OK;
}
