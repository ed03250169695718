/* step.c: simulation set-up and the explicit Update-Stress-Last MPM step
 * (MODEL.md section 2, [DK15] section 3.1).
 *
 * One step: stencil (once) -> point-to-grid (mass, momentum, force) -> grid
 * update with boundary conditions -> grid-to-point (FLIP velocity, position,
 * velocity gradient) -> volume -> constitutive update -> periodic wrap. */
#include "solver/solver.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scenario/scenario.h"

/* ---- set-up -------------------------------------------------------------- */

static int mesh_from_config(mpm_mesh *m, const mpm_config *cfg, mpm_err *err)
{
  memset(m, 0, sizeof *m);
  m->nx = cfg->mesh.nx;
  m->ny = cfg->mesh.ny;
  m->x0 = cfg->mesh.x0;
  m->y0 = cfg->mesh.y0;
  m->dx = cfg->mesh.dx;
  m->dy = cfg->mesh.dy;
  m->topology = mpm_mesh_topology_from_name(cfg->mesh.topology);
  m->diagonal = mpm_mesh_diagonal_from_name(cfg->mesh.diagonal);
  m->mirror_x = cfg->mesh.mirror_x;
  m->periodic_x = cfg->bc.left == MPM_BC_PERIODIC;
  m->periodic_y = cfg->bc.bottom == MPM_BC_PERIODIC;
  if (m->topology < 0)
    return mpm_err_set(err, MPM_EINPUT, "mesh.topology '%s' unknown", cfg->mesh.topology);
  if (m->diagonal < 0)
    return mpm_err_set(err, MPM_EINPUT, "mesh.diagonal '%s' unknown", cfg->mesh.diagonal);
  return mpm_mesh_setup(m, err);
}

static void params_from_config(mpm_material_params *par, const mpm_config *cfg)
{
  memset(par, 0, sizeof *par);
  par->E = cfg->material.E;
  par->nu = cfg->material.nu;
  par->rho_s = cfg->material.rho_s;
  par->rho_c = cfg->material.rho_c;
  par->mu_s = cfg->material.mu_s;
  par->mu_2 = cfg->material.mu_2;
  par->I0 = cfg->material.I0;
  par->d = cfg->material.d;
  par->A = cfg->material.A;
  par->t0 = cfg->material.t0;
  mpm_material_params_derive(par);
}

/* Grow the per-point workspace to the point capacity. */
static int workspace_reserve(mpm_sim *s, size_t cap)
{
  if (cap <= s->wcap)
    return MPM_OK;
  double **arrs[] = {&s->Lxx, &s->Lxy, &s->Lyx, &s->Lyy};
  for (size_t k = 0; k < sizeof arrs / sizeof arrs[0]; k++) {
    double *p = realloc(*arrs[k], cap * sizeof *p);
    if (!p)
      return MPM_ENOMEM;
    *arrs[k] = p;
  }
  s->wcap = cap;
  return MPM_OK;
}

static int nodal_alloc(mpm_sim *s)
{
  size_t n = (size_t)s->mesh.nnodes;
  double **arrs[] = {&s->nm, &s->nmvx, &s->nmvy, &s->nfx, &s->nfy,
                     &s->nvx, &s->nvy, &s->nax, &s->nay};
  for (size_t k = 0; k < sizeof arrs / sizeof arrs[0]; k++)
    if (!(*arrs[k] = calloc(n, sizeof(double))))
      return MPM_ENOMEM;
  return MPM_OK;
}

/* dt = cfl min(dx, dy) / (c_p + |v|max) at the densest, fastest fill. */
static double stable_dt(const mpm_sim *s)
{
  double rho = 0.0, vmax = 0.0;
  for (int f = 0; f < s->cfg.nfill; f++) {
    const mpm_fill_config *fc = &s->cfg.fill[f];
    if (fc->density > rho) rho = fc->density;
    double v = hypot(fc->vx, fc->vy);
    if (v > vmax) vmax = v;
  }
  double h = fmin(s->mesh.dx, s->mesh.dy);
  return s->cfg.time.cfl * h / (mpm_material_wave_speed(&s->par, rho) + vmax);
}

int mpm_sim_create(mpm_sim **out, const mpm_config *cfg, mpm_err *err)
{
  *out = NULL;
  mpm_sim *s = calloc(1, sizeof *s);
  if (!s)
    return mpm_err_set(err, MPM_ENOMEM, "simulation: out of memory");
  s->cfg = *cfg;
  int rc = mesh_from_config(&s->mesh, cfg, err);
  if (rc == MPM_OK) {
    int edge[4] = {cfg->bc.left, cfg->bc.right, cfg->bc.bottom, cfg->bc.top};
    rc = mpm_bc_setup(&s->bc, &s->mesh, edge, err);
  }
  if (rc == MPM_OK && !(s->shape = mpm_shape_lookup(cfg->mesh.shape)))
    rc = mpm_err_set(err, MPM_EINPUT, "mesh.shape '%s' unknown", cfg->mesh.shape);
  if (rc == MPM_OK && !(s->mat = mpm_material_lookup(cfg->material.model)))
    rc = mpm_err_set(err, MPM_EINPUT, "material.model '%s' unknown", cfg->material.model);
  if (rc == MPM_OK) {
    params_from_config(&s->par, cfg);
    rc = s->mat->check(&s->par, err);
  }
  if (rc == MPM_OK && !(s->pts = mpm_points_alloc(1024)))
    rc = mpm_err_set(err, MPM_ENOMEM, "points: out of memory");
  for (int f = 0; rc == MPM_OK && f < cfg->nfill; f++)
    rc = mpm_scenario_fill(s->pts, &s->mesh, &cfg->fill[f], &s->par, cfg->gravity.gy, err);
  if (rc == MPM_OK && (nodal_alloc(s) != MPM_OK ||
                       workspace_reserve(s, s->pts->cap) != MPM_OK ||
                       !(s->st = mpm_stencil_alloc(s->pts->cap))))
    rc = mpm_err_set(err, MPM_ENOMEM, "simulation workspace: out of memory");
  if (rc != MPM_OK) {
    mpm_sim_free(s);
    return rc;
  }
  s->dt = cfg->time.dt > 0.0 ? cfg->time.dt : stable_dt(s);
  for (size_t p = 0; p < s->pts->n; p++)
    s->mass0 += s->pts->mass[p];
  s->mtiny = 1e-12 * s->mass0 / (double)s->pts->n;          /* skip nodes lighter than this */
  *out = s;
  return MPM_OK;
}

void mpm_sim_free(mpm_sim *s)
{
  if (!s)
    return;
  mpm_bc_clear(&s->bc);
  mpm_points_free(s->pts);
  mpm_stencil_free(s->st);
  double *arrs[] = {s->nm, s->nmvx, s->nmvy, s->nfx, s->nfy, s->nvx, s->nvy,
                    s->nax, s->nay, s->Lxx, s->Lxy, s->Lyx, s->Lyy};
  for (size_t k = 0; k < sizeof arrs / sizeof arrs[0]; k++)
    free(arrs[k]);
  free(s);
}

void mpm_sim_gravity(const mpm_sim *s, double t, double *gx, double *gy)
{
  double r = s->cfg.gravity.t_ramp;
  double f = (r > 0.0 && t < r) ? t / r : 1.0;             /* linear ramp 0 -> 1 over t_ramp */
  *gx = f * s->cfg.gravity.gx;
  *gy = f * s->cfg.gravity.gy;
}

/* ---- the step ------------------------------------------------------------ */

/* Step 2: m_i, (mv)_i, f_i = sum [-V_p sigma_p . gradS_ip + S_ip m_p b]. */
static void point_to_grid(mpm_sim *s, double bx, double by)
{
  const mpm_points *P = s->pts;
  const mpm_stencil *st = s->st;
  size_t nn = (size_t)s->mesh.nnodes;
  memset(s->nm, 0, nn * sizeof(double));
  memset(s->nmvx, 0, nn * sizeof(double));
  memset(s->nmvy, 0, nn * sizeof(double));
  memset(s->nfx, 0, nn * sizeof(double));
  memset(s->nfy, 0, nn * sizeof(double));
  for (size_t p = 0; p < P->n; p++) {
    double m = P->mass[p], V = P->vol[p];
    double mvx = m * P->vx[p], mvy = m * P->vy[p];
    double sxx = P->sxx[p], syy = P->syy[p], sxy = P->sxy[p];
    const int *node = st->node + p * MPM_STENCIL_W;
    const double *S = st->S + p * MPM_STENCIL_W;
    const double *gx = st->dSx + p * MPM_STENCIL_W, *gy = st->dSy + p * MPM_STENCIL_W;
    for (int k = 0; k < st->count[p]; k++) {
      int i = node[k];
      s->nm[i] += S[k] * m;
      s->nmvx[i] += S[k] * mvx;
      s->nmvy[i] += S[k] * mvy;
      s->nfx[i] += -V * (sxx * gx[k] + sxy * gy[k]) + S[k] * m * bx;  /* -V sigma.gradS + S m b */
      s->nfy[i] += -V * (sxy * gx[k] + syy * gy[k]) + S[k] * m * by;
    }
  }
}

/* Step 3: boundary conditions, (mv)_i += dt f_i, a_i = f_i/m_i, v_i = (mv)_i/m_i. */
static void grid_update(mpm_sim *s)
{
  mpm_bc_apply(&s->bc, s->nmvx, s->nmvy);
  mpm_bc_apply(&s->bc, s->nfx, s->nfy);
  double dt = s->dt, mt = s->mtiny;
  for (int i = 0; i < s->mesh.nnodes; i++) {
    double m = s->nm[i];
    if (m > mt) {
      s->nmvx[i] += dt * s->nfx[i];
      s->nmvy[i] += dt * s->nfy[i];
      s->nax[i] = s->nfx[i] / m;
      s->nay[i] = s->nfy[i] / m;
      s->nvx[i] = s->nmvx[i] / m;
      s->nvy[i] = s->nmvy[i] / m;
    } else {
      s->nax[i] = s->nay[i] = s->nvx[i] = s->nvy[i] = 0.0;
    }
  }
}

/* Step 4-5: v_p += dt sum S a_i; x_p += dt sum S v_i; L_p = sum v_i (x) gradS;
 * V_p *= exp(dt tr L_p). */
static void grid_to_point(mpm_sim *s)
{
  mpm_points *P = s->pts;
  const mpm_stencil *st = s->st;
  double dt = s->dt;
#pragma omp parallel for schedule(static)
  for (size_t p = 0; p < P->n; p++) {
    const int *node = st->node + p * MPM_STENCIL_W;
    const double *S = st->S + p * MPM_STENCIL_W;
    const double *gx = st->dSx + p * MPM_STENCIL_W, *gy = st->dSy + p * MPM_STENCIL_W;
    double ax = 0, ay = 0, vx = 0, vy = 0, lxx = 0, lxy = 0, lyx = 0, lyy = 0;
    for (int k = 0; k < st->count[p]; k++) {
      int i = node[k];
      ax += S[k] * s->nax[i];
      ay += S[k] * s->nay[i];
      vx += S[k] * s->nvx[i];
      vy += S[k] * s->nvy[i];
      lxx += s->nvx[i] * gx[k];
      lxy += s->nvx[i] * gy[k];
      lyx += s->nvy[i] * gx[k];
      lyy += s->nvy[i] * gy[k];
    }
    P->vx[p] += dt * ax;
    P->vy[p] += dt * ay;
    P->x[p] += dt * vx;
    P->y[p] += dt * vy;
    s->Lxx[p] = lxx;
    s->Lxy[p] = lxy;
    s->Lyx[p] = lyx;
    s->Lyy[p] = lyy;
    P->vol[p] *= exp(dt * (lxx + lyy));                   /* V *= exp(dt tr L) */
  }
}

/* Step 6: constitutive update of every point with L fixed; returns the index
 * of a point whose stress became non-finite, or -1. */
static long constitutive(mpm_sim *s)
{
  mpm_points *P = s->pts;
  long bad = -1;
#pragma omp parallel for schedule(static) reduction(max : bad)
  for (size_t p = 0; p < P->n; p++) {
    mpm_mat3 L = {{{s->Lxx[p], s->Lxy[p], 0.0}, {s->Lyx[p], s->Lyy[p], 0.0}, {0.0, 0.0, 0.0}}};
    mpm_mpoint mp = {
      .sigma = {P->sxx[p], P->syy[p], P->szz[p], P->sxy[p], 0.0, 0.0},
      .rho = P->mass[p] / P->vol[p],                       /* rho_{n+1} = m / V_{n+1} */
      .g = P->g[p], .gdp = P->gdp[p], .state = P->state[p],
    };
    s->mat->update(&s->par, &L, s->dt, &mp);
    P->sxx[p] = mp.sigma.xx;
    P->syy[p] = mp.sigma.yy;
    P->szz[p] = mp.sigma.zz;
    P->sxy[p] = mp.sigma.xy;
    P->g[p] = mp.g;
    P->gdp[p] = mp.gdp;
    P->state[p] = mp.state;
    if (!isfinite(mp.sigma.xx + mp.sigma.yy + mp.sigma.zz + mp.sigma.xy))
      bad = (long)p > bad ? (long)p : bad;
  }
  return bad;
}

int mpm_sim_step(mpm_sim *s, mpm_err *err)
{
  int rc = mpm_stencil_compute(s->st, s->shape, &s->mesh, s->pts, s->t, err);
  if (rc != MPM_OK)
    return rc;
  double bx, by;
  mpm_sim_gravity(s, s->t, &bx, &by);
  point_to_grid(s, bx, by);
  grid_update(s);
  grid_to_point(s);
  long bad = constitutive(s);
  if (bad >= 0)
    return mpm_err_set(err, MPM_ENONFINITE,
                       "point %d: non-finite stress at (%.6g, %.6g) m, t = %.6g s",
                       s->pts->id[bad], s->pts->x[bad], s->pts->y[bad], s->t + s->dt);
  for (size_t p = 0; p < s->pts->n; p++)                    /* step 7: periodic wrap */
    mpm_mesh_wrap(&s->mesh, &s->pts->x[p], &s->pts->y[p]);
  s->t += s->dt;
  s->step++;
  return MPM_OK;
}
