/* field3.c: the element fluidity field on the 3D unit grid (field3.h): the
 * 7-point Laplacian of grid.c and the backward-Euler solve of implicit.c
 * on the boxes of an mpm_mesh3,
 *   lap_e = sum_{a = x, y, z} (g_{a+} - 2 g_e + g_{a-}) / h_a^2,
 *   (I - c L_h) g* = g_e,  lap_e = (g*_e - g_e)/c. */
#include "nonlocal/field3.h"

#include <stdlib.h>

void mpm_nonlocal3_free(mpm_nonlocal3 *ws)
{
  if (!ws)
    return;
  free(ws->sm);
  free(ws->ge);
  free(ws->lap);
  mpm_nonlocal_implicit_free(ws->im);
  free(ws);
}

int mpm_nonlocal3_alloc(mpm_nonlocal3 **out, const mpm_mesh3 *m, const int ghost[6],
                        mpm_err *err)
{
  *out = NULL;
  const int periodic[3] = {m->periodic_x, m->periodic_y, m->periodic_z};
  for (int a = 0; a < 3; a++)
    if ((ghost[2 * a] == MPM_GHOST_PERIODIC || ghost[2 * a + 1] == MPM_GHOST_PERIODIC) !=
        (periodic[a] != 0))
      return mpm_err_set(err, MPM_EINVAL, "nonlocal: periodic %c faces must match the mesh",
                         "xyz"[a]);
  mpm_nonlocal3 *ws = calloc(1, sizeof *ws);
  if (!ws)
    return mpm_err_set(err, MPM_ENOMEM, "nonlocal: no memory for the 3D workspace");
  const int n[3] = {m->nx, m->ny, m->nz};
  const double h[3] = {m->dx, m->dy, m->dz};
  int rc = mpm_nonlocal_grid_set(&ws->grid, 3, n, h, ghost, err);
  if (rc != MPM_OK) {
    mpm_nonlocal3_free(ws);
    return rc;
  }
  const size_t nu = ws->grid.nu;
  ws->sm = calloc(nu, sizeof *ws->sm);
  ws->ge = calloc(nu, sizeof *ws->ge);
  ws->lap = calloc(nu, sizeof *ws->lap);
  if (!ws->sm || !ws->ge || !ws->lap) {
    mpm_nonlocal3_free(ws);
    return mpm_err_set(err, MPM_ENOMEM, "nonlocal: no memory for %zu units", nu);
  }
  *out = ws;
  return MPM_OK;
}

void mpm_nonlocal3_laplacian(mpm_nonlocal3 *ws)
{
  mpm_nonlocal_grid_laplacian(&ws->grid, ws->sm, ws->ge, ws->lap);
}

int mpm_nonlocal3_implicit(mpm_nonlocal3 *ws, double c, mpm_err *err)
{
  if (!ws->im) {
    ws->im = mpm_nonlocal_implicit_alloc_grid(&ws->grid, err);
    if (!ws->im)
      return err && err->code ? err->code : MPM_ENOMEM;
  }
  return mpm_nonlocal_implicit_grid(ws->im, &ws->grid, ws->sm, ws->ge, ws->lap, c, err);
}

const double *mpm_nonlocal3_gstar(const mpm_nonlocal3 *ws)
{
  return ws->im ? mpm_nonlocal_implicit_gstar(ws->im) : NULL;
}

mpm_linalg_stats mpm_nonlocal3_stats(const mpm_nonlocal3 *ws)
{
  if (!ws->im)
    return (mpm_linalg_stats){.failed_col = -1};
  return mpm_nonlocal_implicit_stats(ws->im);
}

/* The unit sums of the dense points of [0, n), each point's mass split by
 * the weights w[k p ...] between its units part[k p ...] (k pairs a point;
 * k = 1, w = NULL: all of it in part[p]), in point order; then g_e. */
static void average(mpm_nonlocal3 *ws, size_t n, int k, const int *part, const double *w,
                    const double *mass, const double *g, const unsigned char *dense)
{
  const size_t nu = ws->grid.nu;
  for (size_t e = 0; e < nu; e++)
    ws->sm[e] = ws->ge[e] = 0.0;            /* ge holds sum m g until the division */
  for (size_t p = 0; p < n; p++) {
    if (!dense[p])
      continue;
    for (int q = 0; q < k; q++) {
      const size_t i = (size_t)k * p + (size_t)q;
      if (w && !(w[i] > 0.0))
        continue;                           /* an unused slot */
      const double wm = w ? w[i] * mass[p] : mass[p];
      ws->sm[part[i]] += wm;                /* sum w m */
      ws->ge[part[i]] += wm * g[p];         /* sum w m g */
    }
  }
  for (size_t e = 0; e < nu; e++)
    ws->ge[e] = ws->sm[e] > 0.0 ? ws->ge[e] / ws->sm[e] : 0.0;
}

void mpm_nonlocal3_average(mpm_nonlocal3 *ws, size_t n, const int *unit, const double *mass,
                           const double *g, const unsigned char *dense)
{
  average(ws, n, 1, unit, NULL, mass, g, dense);
}

void mpm_nonlocal3_average_parts(mpm_nonlocal3 *ws, size_t n, const int *part, const double *w,
                                 const double *mass, const double *g,
                                 const unsigned char *dense)
{
  average(ws, n, MPM_NONLOCAL3_PARTS, part, w, mass, g, dense);
}

int mpm_nonlocal3_filled(const mpm_nonlocal3 *ws)
{
  for (size_t e = 0; e < ws->grid.nu; e++)
    if (ws->sm[e] > 0.0)
      return 1;
  return 0;
}
