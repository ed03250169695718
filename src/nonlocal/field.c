/* field.c: the NGF element field of one (sub)step and the table of diffusion
 * solvers (field.h). The dense flags are independent per point (parallel);
 * the unit sums run band by band (nonlocal.h), so the field does not depend
 * on the number of threads. */
#include "nonlocal/field.h"

#include <stdlib.h>
#include <string.h>

#include "core/names.h"
#include "nonlocal/implicit.h"
#include "nonlocal/steady.h"

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
  const size_t nu = ws->grid.nu;
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

/* ---- steady: g of lap(g) = (g - g_loc)/xi^2 on the nodes, once per step ---- */

/* The steady solver's state: the nodal solve and the per-point and per-node
 * inputs of mpm_nonlocal_steady_solve (made at the first field, when the
 * mesh is known). */
typedef struct steady_state {
  mpm_nonlocal_steady *ss;
  double *w, *gloc;         /* [cap] 1/xi^2 [1/m^2], g_loc [1/s] */
  unsigned char *dense;     /* [cap] */
  size_t cap;
  unsigned char *held;      /* [mesh nnodes] g = 0 */
  int solved;               /* 1 once the nodal field exists */
} steady_state;

static void steady_free(void *state)
{
  steady_state *st = state;
  if (!st)
    return;
  mpm_nonlocal_steady_free(st->ss);
  free(st->w);
  free(st->gloc);
  free(st->dense);
  free(st->held);
  free(st);
}

static const mpm_nonlocal_diffusion diffusion_steady = {
  .name = "steady",
  .description = "steady equation lap(g) = (g - g_loc)/xi^2 on the mesh nodes, once per step "
                 "(Galerkin, CHOLMOD) [D-thesis]",
  .stability_limited = 0,
  .steady = 1,
  .free = steady_free,
};

const mpm_nonlocal_diffusion *const mpm_nonlocal_diffusion_table[] = {
  [MPM_DIFFUSION_EXPLICIT] = &diffusion_explicit,
  [MPM_DIFFUSION_IMPLICIT] = &diffusion_implicit,
  [MPM_DIFFUSION_STEADY] = &diffusion_steady,
  NULL
};

static const char *const diffusion_names[] = {
  [MPM_DIFFUSION_EXPLICIT] = "explicit", [MPM_DIFFUSION_IMPLICIT] = "implicit",
  [MPM_DIFFUSION_STEADY] = "steady"
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
                       double dt_sub, int local, mpm_err *err)
{
  const size_t n = P->n;
#pragma omp parallel for schedule(static)
  for (size_t p = 0; p < n; p++) {
    mpm_sym3 sig = mpm_points_stress(P, p);
    double r = rho ? rho[p] : P->mass[p] / P->vol[p];              /* rho_{n+1} */
    ws->dense[p] = (unsigned char)mt->dense(par, sig, r);
    ws->pn[p] = mpm_sym3_pressure(sig);                            /* p_n */
  }
  const mpm_nonlocal_diffusion *d = ws->diffusion ? ws->diffusion : &diffusion_explicit;
  if (!d->laplacian)
    return mpm_err_set(err, MPM_EINVAL, "nonlocal: the %s solver has no (sub)step field "
                       "(mpm_nonlocal_steady_field)", d->name);
  mpm_nonlocal_average(ws, n, P->mass, P->g, ws->dense);           /* g_e, band order */
  if (local)                                                       /* no diffusion yet */
    memset(ws->lap, 0, ws->grid.nu * sizeof *ws->lap);
  else {
    const int rc = d->laplacian(ws->diffusion_state, ws, mpm_material_ngf_diffusivity(par, dt_sub),
                                err);
    if (rc != MPM_OK)
      return rc;
  }
  if (par->p_sample == MPM_NGF_P_UNIT)
    mpm_nonlocal_pressure(ws, n, P->mass, ws->pn, ws->dense);      /* isp_e */
  return MPM_OK;
}

/* ---- the steady field of one step ---------------------------------------- */

int mpm_nonlocal_is_steady(const mpm_nonlocal *ws)
{
  return ws->diffusion && ws->diffusion->steady;
}

/* The steady state of ws, made for mesh m and n points on first use. */
static steady_state *steady_state_for(mpm_nonlocal *ws, const mpm_mesh *m, size_t n,
                                      mpm_err *err)
{
  steady_state *st = ws->diffusion_state;
  if (!st) {
    st = calloc(1, sizeof *st);
    if (st)
      st->held = malloc(m->nnodes > 0 ? (size_t)m->nnodes : 1);
    if (st && st->held)
      st->ss = mpm_nonlocal_steady_alloc(m, err);
    if (!st || !st->held || !st->ss) {
      steady_free(st);
      if (!err || err->code == MPM_OK)
        mpm_err_set(err, MPM_ENOMEM, "steady fluidity: no memory for %d nodes", m->nnodes);
      return NULL;
    }
    ws->diffusion_state = st;
  }
  if (n > st->cap) {
    double *w = realloc(st->w, n * sizeof *w);
    if (w)
      st->w = w;
    double *gl = realloc(st->gloc, n * sizeof *gl);
    if (gl)
      st->gloc = gl;
    unsigned char *d = realloc(st->dense, n);
    if (d)
      st->dense = d;
    if (!w || !gl || !d) {
      mpm_err_set(err, MPM_ENOMEM, "steady fluidity: no memory for %zu points", n);
      return NULL;
    }
    st->cap = n;
  }
  return st;
}

int mpm_nonlocal_steady_field(mpm_nonlocal *ws, const mpm_material_type *mt,
                              const mpm_material_params *par, mpm_points *P,
                              const mpm_shape_stencil *st, const mpm_mesh *m, int sample,
                              int mass, mpm_err *err)
{
  if (!mt->steady_terms || !mt->update_steady)
    return mpm_err_set(err, MPM_EINVAL, "steady fluidity: model '%s' has no steady form",
                       mt->name);
  const size_t n = P->n;
  steady_state *ssf = steady_state_for(ws, m, n > 0 ? n : 1, err);
  if (!ssf)
    return err && err->code ? err->code : MPM_ENOMEM;
  const double l2 = par->A * par->A * par->d * par->d;          /* (A d)^2 */
#pragma omp parallel for schedule(static)
  for (size_t p = 0; p < n; p++) {
    mpm_sym3 sig = mpm_points_stress(P, p);                      /* sigma_n */
    double c, gl;
    mt->steady_terms(par, sig, &c, &gl);
    ssf->dense[p] = P->state[p] == MPM_STATE_DENSE && mpm_sym3_pressure(sig) > 0.0;
    ssf->w[p] = l2 > 0.0 ? c / l2 : 0.0;                         /* 1/xi^2 = c/(A d)^2 */
    ssf->gloc[p] = gl;
  }
  if (!(l2 > 0.0)) {                                             /* A = 0: local, g = g_loc */
    for (size_t p = 0; p < n; p++)
      P->g[p] = ssf->dense[p] ? ssf->gloc[p] : 0.0;
    ssf->solved = 0;
    return MPM_OK;
  }
  mpm_nonlocal_held_nodes(ws, m, ssf->held);
  int rc = mpm_nonlocal_steady_solve(ssf->ss, st, m, n, P->vol, ssf->w, ssf->gloc,
                                     ssf->dense, ssf->held, mass, err);
  ssf->solved = rc == MPM_OK;
  if (rc != MPM_OK)
    return rc;
#pragma omp parallel for schedule(static)
  for (size_t p = 0; p < n; p++)
    P->g[p] = mpm_nonlocal_steady_point(ssf->ss, m, st, P, p, sample);
  return MPM_OK;
}

const double *mpm_nonlocal_steady_field_nodal(const mpm_nonlocal *ws)
{
  const steady_state *st = mpm_nonlocal_is_steady(ws) ? ws->diffusion_state : NULL;
  return st && st->solved ? mpm_nonlocal_steady_nodal(st->ss) : NULL;
}

mpm_linalg_stats mpm_nonlocal_steady_field_stats(const mpm_nonlocal *ws)
{
  const steady_state *st = mpm_nonlocal_is_steady(ws) ? ws->diffusion_state : NULL;
  if (!st)
    return (mpm_linalg_stats){.failed_col = -1};
  return mpm_nonlocal_steady_stats(st->ss);
}
