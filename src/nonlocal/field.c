/* field.c: the NGF element field of one (sub)step and the table of diffusion
 * solvers (field.h). The dense flags are independent per point (parallel);
 * the unit sums run in point order on one thread (nonlocal.h), so the field
 * does not depend on the number of threads. */
#include "nonlocal/field.h"

#include "core/names.h"
#include "nonlocal/implicit.h"

/* ---- explicit: lap_e = L_h g_e ------------------------------------------- */

static int explicit_laplacian(void *state, mpm_nonlocal *ws, double c, mpm_err *err)
{
  (void)state;
  (void)c;
  (void)err;
  mpm_nonlocal_laplacian(ws);
  return MPM_OK;
}

static const mpm_nonlocal_diffusion diffusion_explicit = {
  .name = "explicit",
  .description = "forward Euler: lap_e = L_h g_e; stable for c (2/dx^2 + 2/dy^2) <= 1",
  .stability_limited = 1,
  .laplacian = explicit_laplacian,
};

/* ---- implicit: lap_e = L_h g*, (I - c L_h) g* = g_e ------------------------ */

static int implicit_alloc(void **state, const mpm_nonlocal *ws, mpm_err *err)
{
  mpm_nonlocal_implicit *im = mpm_nonlocal_implicit_alloc(ws, err);
  *state = im;
  return im ? MPM_OK : err && err->code ? err->code : MPM_ENOMEM;
}

static void implicit_free(void *state)
{
  mpm_nonlocal_implicit_free(state);
}

static int implicit_laplacian(void *state, mpm_nonlocal *ws, double c, mpm_err *err)
{
  const size_t nu = (size_t)ws->nx * (size_t)ws->ny;
  size_t e = 0;
  while (e < nu && !(ws->sm[e] > 0.0))
    e++;
  if (e == nu) {                       /* no dense unit: nothing diffuses, lap_e = 0 */
    mpm_nonlocal_laplacian(ws);
    return MPM_OK;
  }
  return mpm_nonlocal_implicit_laplacian(state, ws, c, err);
}

static const mpm_nonlocal_diffusion diffusion_implicit = {
  .name = "implicit",
  .description = "backward Euler on the unit grid (CHOLMOD); stable for any c",
  .stability_limited = 0,
  .alloc = implicit_alloc,
  .free = implicit_free,
  .laplacian = implicit_laplacian,
};

const mpm_nonlocal_diffusion *const mpm_nonlocal_diffusion_table[] = {
  [MPM_DIFFUSION_EXPLICIT] = &diffusion_explicit,
  [MPM_DIFFUSION_IMPLICIT] = &diffusion_implicit,
  NULL
};

static const char *const diffusion_names[] = {
  [MPM_DIFFUSION_EXPLICIT] = "explicit", [MPM_DIFFUSION_IMPLICIT] = "implicit"
};

int mpm_nonlocal_diffusion_from_name(const char *name)
{
  return mpm_names_index(diffusion_names, MPM_NAMES_COUNT(diffusion_names), name);
}

const char *mpm_nonlocal_diffusion_name(int kind)
{
  return mpm_names_at(diffusion_names, MPM_NAMES_COUNT(diffusion_names), kind);
}

int mpm_nonlocal_set_diffusion(mpm_nonlocal *ws, int kind, mpm_err *err)
{
  if (!mpm_nonlocal_diffusion_name(kind))
    return mpm_err_set(err, MPM_EINVAL, "nonlocal: unknown diffusion solver %d", kind);
  const mpm_nonlocal_diffusion *d = mpm_nonlocal_diffusion_table[kind];
  if (ws->diffusion && ws->diffusion->free)
    ws->diffusion->free(ws->diffusion_state);
  ws->diffusion = d;
  ws->diffusion_state = NULL;
  return d->alloc ? d->alloc(&ws->diffusion_state, ws, err) : MPM_OK;
}

/* ---- one (sub)step ------------------------------------------------------- */

int mpm_nonlocal_field(mpm_nonlocal *ws, const mpm_material_type *mt,
                       const mpm_material_params *par, const mpm_points *P, const double *rho,
                       double dt_sub, mpm_err *err)
{
  const size_t n = P->n;
#pragma omp parallel for schedule(static)
  for (size_t p = 0; p < n; p++) {
    mpm_sym3 sig = mpm_points_stress(P, p);
    double r = rho ? rho[p] : P->mass[p] / P->vol[p];              /* rho_{n+1} */
    ws->dense[p] = (unsigned char)mt->dense(par, sig, r);
    ws->pn[p] = mpm_sym3_pressure(sig);                            /* p_n */
  }
  mpm_nonlocal_average(ws, n, P->mass, P->g, ws->dense);           /* g_e, point order */
  const mpm_nonlocal_diffusion *d = ws->diffusion ? ws->diffusion : &diffusion_explicit;
  int rc = d->laplacian(ws->diffusion_state, ws, mpm_material_ngf_diffusivity(par, dt_sub), err);
  if (rc != MPM_OK)
    return rc;
  if (par->p_sample == MPM_NGF_P_UNIT)
    mpm_nonlocal_pressure(ws, n, P->mass, ws->pn, ws->dense);      /* isp_e */
  return MPM_OK;
}
