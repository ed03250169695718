/* step3.c: the 3D module's explicit Update-Stress-Last step (MODEL.md
 * section 2 on the box mesh of mesh/box.h; mesh.nz > 0).
 *
 * The plane step's sequence on the same kernels: the stored stencil of the
 * 3D shape (shape3.h), point-to-grid and the grid update of transfer.inc
 * with DIM 3 in transfer.c's parallel grid phase (bands of unit layers along
 * z), then point by point: the gather of transfer.inc, the FLIP/PIC velocity
 * blend, x += dt v_grid, the volume ratio of transfer.h, CPDI1's convected
 * extent (mpm_shape_extent_convect_dim), the model's update on the full 3x3
 * L (every local model of the table works on 3x3 tensors), then the walls
 * (mpm_bc_clamp_axis per axis) and periodic wraps. y is the vertical as in
 * the plane, z the third axis. Results do not depend on the thread count:
 * point-to-grid sums band by band as in the plane, the rest is per point. */
#include "solver/solver.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scenario/scenario.h"
#include "solver/transfer.h"

/* ---- set-up -------------------------------------------------------------- */

int mpm_sim3_build(mpm_sim *s, mpm_err *err)
{
  const mpm_config *cfg = &s->cfg;
  mpm_mesh3 *m = &s->mesh3;
  int rc = mpm_mesh3_from_config(m, cfg, err);
  if (rc == MPM_OK) {
    const int face[6] = {cfg->bc.left,   cfg->bc.right, cfg->bc.bottom,
                         cfg->bc.top,    cfg->bc.front, cfg->bc.back};
    rc = mpm_bc3_setup(&s->bc3, m, face, err);
  }
  if (rc == MPM_OK && !(s->shape3 = mpm_shape3_lookup(cfg->mesh.shape)))
    rc = mpm_err_set(err, MPM_EINPUT, "mesh.shape '%s' unknown in 3D", cfg->mesh.shape);
  if (rc == MPM_OK && !(s->pts = mpm_points_alloc_dim(1024, 3)))
    rc = mpm_err_set(err, MPM_ENOMEM, "points: out of memory");
  for (int f = 0; rc == MPM_OK && f < cfg->nfill; f++) {
    mpm_fill3_region r;
    mpm_scenario_region3(&cfg->fill[f], &r);
    rc = mpm_scenario_fill3(s->pts, m, &r, err);
  }
  if (rc != MPM_OK)
    return rc;
  const size_t nn = (size_t)m->nnodes;
  if (!(s->nm = calloc(nn, sizeof *s->nm)) || !(s->nq3 = calloc(nn, sizeof *s->nq3)) ||
      !(s->st = mpm_shape_stencil_alloc(0)) || !(s->bands = mpm_mesh_bands_alloc()))
    return mpm_err_set(err, MPM_ENOMEM, "simulation workspace: out of memory");
  return MPM_OK;
}

/* ---- the step ------------------------------------------------------------ */

/* The stress of point p as a tensor, and back. */
static inline mpm_sym3 stress_of(const mpm_points *P, size_t p)
{
  return (mpm_sym3){P->sxx[p], P->syy[p], P->szz[p], P->sxy[p], P->syz[p], P->szx[p]};
}

static inline void stress_set(mpm_points *P, size_t p, mpm_sym3 s)
{
  P->sxx[p] = s.xx;
  P->syy[p] = s.yy;
  P->szz[p] = s.zz;
  P->sxy[p] = s.xy;
  P->syz[p] = s.yz;
  P->szx[p] = s.zx;
}

/* Steps 4-6 for point p: gather, move, volume, extent, constitutive update
 * in n_sub substeps of h with L fixed. Returns 0 if its stress became
 * non-finite. The grid velocity that moved it goes to vg. */
static int advance_point(mpm_sim *s, size_t p, double fl, double h, double vg[3])
{
  mpm_points *P = s->pts;
  const double dt = s->dt;
  double ag[3], L[9];
  mpm_sim_in_gather3(s, p, vg, ag, L);
  double *const x[3] = {&P->x[p], &P->y[p], &P->z[p]};
  double *const v[3] = {&P->vx[p], &P->vy[p], &P->vz[p]};
  for (int d = 0; d < 3; d++) {
    const double fv = *v[d] + dt * ag[d];                 /* v_FLIP */
    *v[d] = fl == 1.0 ? fv : fl * fv + (1.0 - fl) * vg[d];
    *x[d] += dt * vg[d];
  }
  P->vol[p] *= mpm_sim_volume_ratio(dt * (L[0] + L[4] + L[8]));   /* V *= exp(dt tr L) */
  if (s->shape3->convect) {                               /* CPDI1: r_k <- (I + dt L) r_k */
    double *const rp[9] = {&P->r1x[p], &P->r1y[p], &P->r1z[p], &P->r2x[p], &P->r2y[p],
                           &P->r2z[p], &P->r3x[p], &P->r3y[p], &P->r3z[p]};
    double r[9];
    for (int k = 0; k < 9; k++)
      r[k] = *rp[k];
    mpm_shape_extent_convect_dim(3, r, L, dt);
    for (int k = 0; k < 9; k++)
      *rp[k] = r[k];
  }
  mpm_mat3 Lm;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      Lm.m[i][j] = L[3 * i + j];
  mpm_mpoint pt = {.sigma = stress_of(P, p), .rho = P->mass[p] / P->vol[p], .g = P->g[p],
                   .gdp = P->gdp[p], .state = P->state[p]};
  for (int k = 0; k < s->n_sub; k++)
    s->mat->update(&s->par, &Lm, h, &pt);
  stress_set(P, p, pt.sigma);
  P->g[p] = pt.g;
  P->gdp[p] = pt.gdp;
  P->state[p] = pt.state;
  return isfinite(pt.sigma.xx + pt.sigma.yy + pt.sigma.zz + pt.sigma.xy + pt.sigma.yz +
                  pt.sigma.zx);
}

/* Step 7 for point p moved by the grid velocity vg: the walls hold it (a
 * disconnected point's velocity into a wall limited to the grid's, as in
 * the plane), periodic axes wrap it. */
static void bookkeeping(mpm_sim *s, size_t p, const double vg[3])
{
  mpm_points *P = s->pts;
  const mpm_mesh3 *m = &s->mesh3;
  const int *face = s->bc3.face;
  double *const x[3] = {&P->x[p], &P->y[p], &P->z[p]};
  double *const v[3] = {&P->vx[p], &P->vy[p], &P->vz[p]};
  const double lo[3] = {m->x0, m->y0, m->z0}, len[3] = {m->lx, m->ly, m->lz};
  const int periodic[3] = {m->periodic_x, m->periodic_y, m->periodic_z};
  for (int d = 0; d < 3; d++) {
    if (periodic[d]) {
      mpm_mesh_axis_wrap_coord(x[d], lo[d], len[d]);
      continue;
    }
    double vd = *v[d];
    mpm_bc_clamp_axis(x[d], &vd, vg[d], lo[d], lo[d] + len[d], mpm_bc_is_wall(face[2 * d]),
                      mpm_bc_is_wall(face[2 * d + 1]));
    if (P->state[p] != MPM_STATE_DENSE)
      *v[d] = vd;
  }
}

enum { CHUNK3 = 64 };

int mpm_sim3_step(mpm_sim *s, mpm_err *err)
{
  mpm_points *P = s->pts;
  int rc = mpm_shape3_stencil_compute(s->st, s->shape3, &s->mesh3, P, s->t, err);
  if (rc == MPM_EOUTSIDE && mpm_sim_check_state(s, s->t, err) != MPM_OK)
    return MPM_ENONFINITE;                /* "outside" at a non-finite position: say that */
  if (rc != MPM_OK)
    return rc;
  const int reach = s->st->reach;         /* node layers k - reach .. k + 1 + reach */
  if ((rc = mpm_mesh_bands_sort(s->bands, s->mesh3.nz, s->mesh3.periodic_z, reach, reach + 1,
                                P->n, s->st->row, err)) != MPM_OK)
    return rc;
  double b[3];
  mpm_sim_gravity3(s, s->t, b);
  mpm_sim_in_grid3(s, b);
  const double fl = s->cfg.time.flip, h = s->dt / s->n_sub;
  const size_t n = P->n, nc = (n + CHUNK3 - 1) / CHUNK3;
  long bad = -1;
  unsigned scan = 0;
#pragma omp parallel for schedule(static) reduction(max : bad) reduction(| : scan)
  for (size_t c = 0; c < nc; c++) {
    const size_t a = c * CHUNK3, e = a + CHUNK3 < n ? a + CHUNK3 : n;
    for (size_t p = a; p < e; p++) {
      double vg[3];
      if (!advance_point(s, p, fl, h, vg))
        bad = (long)p > bad ? (long)p : bad;
      bookkeeping(s, p, vg);
    }
    scan |= mpm_sim_too_fast(s, a, e) ? MPM_SIM_SCAN_FAST : 0u;
  }
  if (bad >= 0)                           /* a non-finite stress: what, where, why */
    return mpm_sim_check_state(s, s->t + s->dt, err);
  s->scan = scan;
  s->t += s->dt;
  s->step++;
  return mpm_sim_check_speeds(s, s->t, err);
}
