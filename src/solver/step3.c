/* step3.c: the 3D module's explicit Update-Stress-Last step (MODEL.md
 * section 2 on the box mesh of mesh/box.h; mesh.nz > 0).
 *
 * The plane step's sequence on the same kernels: the stored stencil of the
 * 3D shape (shape3.h), point-to-grid and the grid update of transfer.inc
 * with DIM 3 in transfer.c's parallel grid phase (bands of unit layers along
 * z), then point by point: the gather of transfer.inc, the FLIP/PIC velocity
 * blend or APIC's affine matrix, x += dt v_grid, the volume ratio of
 * transfer.h, CPDI1's convected extent (mpm_shape_extent_convect_dim), the
 * model's update on the full 3x3 L (every local model of the table works on
 * 3x3 tensors), then the walls
 * (mpm_bc_clamp_axis per axis; not for a point leaving through the open
 * outlet) and periodic wraps; points out through the outlet are removed
 * after the step (remove.c). With the hyperelastic NGF, a per-unit state density or
 * the B-bar dilatation every point moves first (moved_phase), then the unit
 * sums run in point order and the points are updated. y is the vertical as
 * in the plane, z the third axis. Results do not depend on the thread count:
 * point-to-grid sums band by band as in the plane, the unit sums in point
 * order, the rest is per point. */
#include "solver/solver.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "material/density.h"
#include "material/hyper.h"
#include "nonlocal/field3.h"
#include "scenario/scenario.h"
#include "solver/transfer.h"

/* ---- set-up -------------------------------------------------------------- */

/* The workspace of a 3D run whose points all move before any update: a
 * nonlocal model (its unit field) or the unit density (its unit sums), and
 * per point its L (row-major, kept over the substeps), unit, dense flag and
 * density. */
struct mpm_sim3_work {
  mpm_nonlocal3 *nl;         /* NULL for a local model */
  mpm_material_density *dens;  /* material.state_density's unit sums; NULL: "point" */
  double *L;                 /* [9 cap] */
  int *unit;                 /* [cap] */
  unsigned char *dense;      /* [cap] */
  double *rho;               /* [cap] rho_{n+1} of the state decision */
  int extent;                /* material.g_average = "extent": the points' unit shares */
  int *part;                 /* [8 cap] extent rule: the units of point p at 8 p ... */
  double *pw;                /* [8 cap] ... and their weights (mpm_nonlocal_grid_parts) */
  size_t cap;
  unsigned char *open;       /* [units] a disc outlet's open unit faces for g, or NULL */
};

void mpm_sim3_work_free(mpm_sim3_work *w)
{
  if (!w)
    return;
  mpm_nonlocal3_free(w->nl);
  mpm_material_density_free(w->dens);
  free(w->L);
  free(w->unit);
  free(w->dense);
  free(w->rho);
  free(w->part);
  free(w->pw);
  free(w->open);
  free(w);
}

/* The workspace: the unit field of a nonlocal model, with the ghost rules
 * of the faces (no-slip: g = 0 unless material.g_wall = "neumann"), and the
 * unit sums of the state density. */
static int work_alloc(mpm_sim *s, mpm_err *err)
{
  if (!(s->w3 = calloc(1, sizeof *s->w3)))
    return mpm_err_set(err, MPM_ENOMEM, "simulation: no memory for the 3D workspace");
  const mpm_mesh3 *m = &s->mesh3;
  if (s->cfg.material.state_density != MPM_DENSITY_POINT) {
    const int n[3] = {m->nx, m->ny, m->nz};
    const int periodic[3] = {m->periodic_x, m->periodic_y, m->periodic_z};
    const int rc = mpm_material_density_alloc_grid(&s->w3->dens, n, periodic,
                                                   m->dx * m->dy * m->dz, err);
    if (rc != MPM_OK)
      return rc;
  }
  if (!s->mat->nonlocal)
    return MPM_OK;
  s->w3->extent = s->cfg.material.g_average == MPM_NONLOCAL_EXTENT;
  const int *face = s->bc3.face;
  int ghost[6];
  for (int f = 0; f < 6; f++) {
    ghost[f] = mpm_nonlocal_ghost_of_bc(face[f]);
    if (ghost[f] == MPM_GHOST_DIRICHLET && s->cfg.material.g_wall == MPM_NONLOCAL_WALL_NEUMANN)
      ghost[f] = MPM_GHOST_NEUMANN;
  }
  return mpm_nonlocal3_alloc(&s->w3->nl, m, ghost, err);
}

const mpm_nonlocal_grid *mpm_sim3_field_grid(const mpm_sim *s)
{
  return s->w3 && s->w3->nl ? &s->w3->nl->grid : NULL;
}

/* Room for the per-point arrays of n points. */
static int work_reserve(mpm_sim3_work *w, size_t n, mpm_err *err)
{
  if (n <= w->cap && w->L)
    return MPM_OK;
  n = n ? n : 1;
  double *L = realloc(w->L, 9 * n * sizeof *L);
  if (L)
    w->L = L;
  int *u = realloc(w->unit, n * sizeof *u);
  if (u)
    w->unit = u;
  unsigned char *d = realloc(w->dense, n);
  if (d)
    w->dense = d;
  double *r = realloc(w->rho, n * sizeof *r);
  if (r)
    w->rho = r;
  int okp = 1;
  if (w->extent) {
    int *pt = realloc(w->part, MPM_NONLOCAL3_PARTS * n * sizeof *pt);
    if (pt)
      w->part = pt;
    double *pw = realloc(w->pw, MPM_NONLOCAL3_PARTS * n * sizeof *pw);
    if (pw)
      w->pw = pw;
    okp = pt && pw;
  }
  if (!L || !u || !d || !r || !okp)
    return mpm_err_set(err, MPM_ENOMEM, "simulation: no memory for %zu points' gradients", n);
  w->cap = n;
  return MPM_OK;
}

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
  const int e = cfg->outlet.edge;
  if (rc == MPM_OK && e != MPM_OUTLET_NONE) {
    /* edges left, right, bottom, top, front, back are the faces -x ... +z */
    const int f = e - MPM_OUTLET_LEFT + MPM_FACE_XLO;
    const double lo[2] = {cfg->outlet.from, cfg->outlet.from2};
    const double hi[2] = {cfg->outlet.to, cfg->outlet.to2};
    const int held = cfg->outlet.ends == MPM_OUTLET_ENDS_FIXED;
    if (cfg->outlet.shape == MPM_OUTLET_DISC) {
      const double c[2] = {0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])};
      rc = mpm_bc3_set_outlet_disc(&s->bc3, m, f, c, 0.5 * (hi[0] - lo[0]), cfg->outlet.closed,
                                   held, err);
    } else {
      rc = mpm_bc3_set_outlet_rectangle(&s->bc3, m, f, lo, hi, cfg->outlet.closed, held, err);
    }
  }
  if (rc == MPM_OK && cfg->wall.nvert > 0)    /* the wall's prism along z */
    rc = mpm_bc3_add_polygon(&s->bc3, m, cfg->wall.nvert, cfg->wall.px, cfg->wall.py,
                             cfg->wall.kind, NULL, err);
  if (rc == MPM_OK && !(s->shape3 = mpm_shape3_lookup(cfg->mesh.shape)))
    rc = mpm_err_set(err, MPM_EINPUT, "mesh.shape '%s' unknown in 3D", cfg->mesh.shape);
  if (rc == MPM_OK && !(s->pts = mpm_points_alloc_dim(1024, 3)))
    rc = mpm_err_set(err, MPM_ENOMEM, "points: out of memory");
  for (int f = 0; rc == MPM_OK && f < cfg->nfill; f++) {
    mpm_fill3_region r;
    mpm_scenario_region3(&cfg->fill[f], &r);
    const size_t first = s->pts->n;
    rc = mpm_scenario_fill3(s->pts, m, &r, err);
    if (rc == MPM_OK)
      rc = mpm_scenario_prestress3(s->pts, first, m, &cfg->fill[f], &s->par, cfg->gravity.gy,
                                   s->mat->hyper, err);
  }
  if (rc != MPM_OK)
    return rc;
  const size_t nn = (size_t)m->nnodes;
  if (!(s->nm = calloc(nn, sizeof *s->nm)) || !(s->nq3 = calloc(nn, sizeof *s->nq3)) ||
      !(s->st = mpm_shape_stencil_alloc(0)) || !(s->bands = mpm_mesh_bands_alloc()))
    return mpm_err_set(err, MPM_ENOMEM, "simulation workspace: out of memory");
  const size_t nu = (size_t)m->nx * (size_t)m->ny * (size_t)m->nz;
  if (cfg->mesh.dilatation != MPM_DILATATION_POINT &&
      (!(s->usum = malloc(2 * nu * sizeof *s->usum)) ||
       (cfg->mesh.dilatation == MPM_DILATATION_ELEMENT &&
        !(s->uel = calloc(mpm_sim_in_el_width(s) * nu, sizeof *s->uel)))))
    return mpm_err_set(err, MPM_ENOMEM, "simulation: no memory for the unit sums");
  return s->mat->nonlocal || s->cfg.material.state_density != MPM_DENSITY_POINT || s->usum
             ? work_alloc(s, err) : MPM_OK;
}

double *mpm_sim_in_l3(const mpm_sim *s)
{
  return s->w3->L;
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

/* Steps 4-5 for point p: gather (with APIC, C_p), FLIP/PIC velocity,
 * x += dt v_grid, volume, CPDI1 extent. L_p to L (row-major), the grid
 * velocity that moved it to vg. */
static void move_point(mpm_sim *s, size_t p, double fl, double L[9], double vg[3])
{
  mpm_points *P = s->pts;
  const double dt = s->dt;
  double ag[3];
  mpm_sim_in_gather3(s, p, vg, ag, L);
  if (s->cfg.time.transfer == MPM_TRANSFER_APIC)
    mpm_sim_in_affine3(s, p, vg, L);                      /* C_p = sum v_i (x) gradS_ip */
  double *const x[3] = {&P->x[p], &P->y[p], &P->z[p]};
  double *const v[3] = {&P->vx[p], &P->vy[p], &P->vz[p]};
  for (int d = 0; d < 3; d++) {
    *v[d] = mpm_sim_in_flip(*v[d], ag[d], vg[d], dt, fl);
    *x[d] += dt * vg[d];
  }
  if (!s->usum)              /* (with B-bar later, by mpm_sim_in_unit_dilatation) */
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
}

static mpm_mat3 mat3_of(const double L[9])
{
  mpm_mat3 m;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      m.m[i][j] = L[3 * i + j];
  return m;
}

static int finite_stress(mpm_sym3 s)
{
  return isfinite(s.xx + s.yy + s.zz + s.xy + s.yz + s.zx);
}

/* Step 6 of a local model for point p: n_sub substeps of h with L fixed and
 * the density rho_{n+1} of the state decision. Returns 0 if its stress
 * became non-finite. */
static int update_local(mpm_sim *s, size_t p, const double L[9], double h, double rho)
{
  mpm_points *P = s->pts;
  const mpm_mat3 Lm = mat3_of(L);
  mpm_mpoint pt = {.sigma = stress_of(P, p), .rho = rho, .g = P->g[p],
                   .gdp = P->gdp[p], .state = P->state[p]};
  for (int k = 0; k < s->n_sub; k++)
    s->mat->update(&s->par, &Lm, h, &pt);
  stress_set(P, p, pt.sigma);
  P->g[p] = pt.g;
  P->gdp[p] = pt.gdp;
  P->state[p] = pt.state;
  return finite_stress(pt.sigma);
}

/* One substep h of the hyperelastic NGF update of point p (L fixed, lap the
 * Laplacian of g of its unit). Returns 0 if its stress became non-finite. */
static int update_hyper(mpm_sim *s, size_t p, const double L[9], double h, double lap,
                        double rho)
{
  mpm_points *P = s->pts;
  const mpm_mat3 Lm = mat3_of(L);
  mpm_material_hyper_point hp = {
    .F = {{{P->fxx[p], P->fxy[p], P->fxz[p]}, {P->fyx[p], P->fyy[p], P->fyz[p]},
           {P->fzx[p], P->fzy[p], P->fzz[p]}}},
    .Fp = {{{P->fpxx[p], P->fpxy[p], P->fpxz[p]}, {P->fpyx[p], P->fpyy[p], P->fpyz[p]},
            {P->fpzx[p], P->fpzy[p], P->fpzz[p]}}},
    .sigma = stress_of(P, p), .rho = rho, .g = P->g[p], .lap = lap,
    .isp = 0.0, .gdp = P->gdp[p], .state = P->state[p]};
  hp = mpm_material_hyper_step(&s->par, &Lm, h, hp);
  double *const F[9] = {P->fxx, P->fxy, P->fxz, P->fyx, P->fyy, P->fyz, P->fzx, P->fzy, P->fzz};
  double *const Fp[9] = {P->fpxx, P->fpxy, P->fpxz, P->fpyx, P->fpyy, P->fpyz,
                         P->fpzx, P->fpzy, P->fpzz};
  for (int k = 0; k < 9; k++) {
    F[k][p] = hp.F.m[k / 3][k % 3];
    Fp[k][p] = hp.Fp.m[k / 3][k % 3];
  }
  stress_set(P, p, hp.sigma);
  P->g[p] = hp.g;
  P->gdp[p] = hp.gdp;
  P->state[p] = hp.state;
  return finite_stress(hp.sigma);
}

/* Step 7 for point p moved by the grid velocity vg: the walls hold it (a
 * disconnected point's velocity into a wall limited to the grid's, as in
 * the plane), periodic axes wrap it, and the absorbing layer takes its
 * upward velocity as in the plane. */
static void bookkeeping(mpm_sim *s, size_t p, const double vg[3])
{
  mpm_points *P = s->pts;
  const mpm_mesh3 *m = &s->mesh3;
  const int *face = s->bc3.face;
  double *const x[3] = {&P->x[p], &P->y[p], &P->z[p]};
  double *const v[3] = {&P->vx[p], &P->vy[p], &P->vz[p]};
  const double lo[3] = {m->x0, m->y0, m->z0}, len[3] = {m->lx, m->ly, m->lz};
  const int periodic[3] = {m->periodic_x, m->periodic_y, m->periodic_z};
  const double xp[3] = {*x[0], *x[1], *x[2]};
  if (mpm_bc3_left_through_outlet(&s->bc3, m, xp))
    return;                                /* leaves through the open outlet */
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
  *v[1] = mpm_sim_in_absorbed(s->cfg.absorb.above, s->cfg.absorb.factor, *x[1], *v[1]);
}

enum { CHUNK3 = 64 };

/* Steps 4-7 of a local model, point by point on chunks; returns the largest
 * index of a point whose stress became non-finite, or -1. */
static long local_phase(mpm_sim *s)
{
  const double fl = mpm_sim_in_flip_share(s), h = s->dt / s->n_sub;
  const size_t n = s->pts->n, nc = (n + CHUNK3 - 1) / CHUNK3;
  long bad = -1;
  unsigned scan = 0;
#pragma omp parallel for schedule(static) reduction(max : bad) reduction(| : scan)
  for (size_t c = 0; c < nc; c++) {
    const size_t a = c * CHUNK3, e = a + CHUNK3 < n ? a + CHUNK3 : n;
    for (size_t p = a; p < e; p++) {
      double L[9], vg[3];
      const mpm_points *P = s->pts;
      move_point(s, p, fl, L, vg);
      if (!update_local(s, p, L, h, P->mass[p] / P->vol[p]))
        bad = (long)p > bad ? (long)p : bad;
      bookkeeping(s, p, vg);
    }
    scan |= (mpm_sim_too_fast(s, a, e) ? MPM_SIM_SCAN_FAST : 0u) |
            (mpm_sim_may_leave(s, a, e) ? MPM_SIM_SCAN_LEAVE : 0u);
  }
  s->scan = scan;
  return bad;
}

/* Extent rule (material.g_average = "extent"): each point in the mesh at
 * x_{n+1} splits its mass between the units its box overlaps, the box of
 * half-widths |r1_a| + |r2_a| + |r3_a| bounding its parallelepiped extent
 * (mpm_nonlocal_grid_parts); an extent wider than a unit is an error. */
static int locate_extents(mpm_sim *s, mpm_err *err)
{
  const mpm_points *P = s->pts;
  const mpm_mesh3 *m = &s->mesh3;
  mpm_sim3_work *w = s->w3;
  const double ih[3] = {m->idx, m->idy, m->idz};
  for (size_t p = 0; p < P->n; p++) {
    if (w->unit[p] < 0)
      continue;
    const double x[3] = {P->x[p], P->y[p], P->z[p]};
    const double r[3][3] = {{P->r1x[p], P->r1y[p], P->r1z[p]},
                            {P->r2x[p], P->r2y[p], P->r2z[p]},
                            {P->r3x[p], P->r3y[p], P->r3z[p]}};
    int c[3];
    double l[3], half[3], hw[3];                   /* half-widths [m] and in units */
    mpm_mesh3_locate(m, x, c, l);
    for (int a = 0; a < 3; a++) {
      half[a] = fabs(r[0][a]) + fabs(r[1][a]) + fabs(r[2][a]);
      hw[a] = half[a] * ih[a];
    }
    for (int a = 0; a < 3; a++)
      if (!(hw[a] <= 0.5 + 1e-12))
        return mpm_err_set(err, MPM_EINVAL, "point %d: extent %.6g x %.6g x %.6g m is wider "
                           "than a unit (material.g_average = \"extent\"), t = %.6g s", P->id[p],
                           2.0 * half[0], 2.0 * half[1], 2.0 * half[2], s->t + s->dt);
    const size_t k = MPM_NONLOCAL3_PARTS * p;
    mpm_nonlocal_grid_parts(&w->nl->grid, c, l, hw, w->part + k, w->pw + k);
  }
  return MPM_OK;
}

/* Steps 4-7 when every point moves before any update (a nonlocal model, the
 * unit density): every point moves (its L kept, walls and wraps applied),
 * the units of x_{n+1} are found, and then
 *   - a local model: the density of the state decision (the unit rule:
 *     sum m_p / sum V_p over the unit, density.h) and the update;
 *   - the hyperelastic NGF: per substep the unit field of the dense points
 *     (g_e, and lap_e by the diffusion of material.diffusion; lap = 0 while
 *     t < t_seed: the local model, [DK-silo] section 6) and the update.
 * Returns as local_phase; *rc an error of the field. */
static long moved_phase(mpm_sim *s, int *rc, mpm_err *err)
{
  mpm_points *P = s->pts;
  mpm_sim3_work *w = s->w3;
  const size_t n = P->n, nc = (n + CHUNK3 - 1) / CHUNK3;
  if ((*rc = work_reserve(w, n, err)) != MPM_OK)
    return -1;
  const double fl = mpm_sim_in_flip_share(s), h = s->dt / s->n_sub;
  unsigned scan = 0;
#pragma omp parallel for schedule(static) reduction(| : scan)
  for (size_t c = 0; c < nc; c++) {
    const size_t a = c * CHUNK3, e = a + CHUNK3 < n ? a + CHUNK3 : n;
    for (size_t p = a; p < e; p++) {
      double vg[3];
      move_point(s, p, fl, w->L + 9 * p, vg);
      bookkeeping(s, p, vg);
    }
    scan |= mpm_sim_too_fast(s, a, e) ? MPM_SIM_SCAN_FAST : 0u;
  }
  s->scan = scan | MPM_SIM_SCAN_LEAVE;
  if (s->usum)                              /* B-bar: tr L_p and V_p per unit */
    mpm_sim_in_unit_dilatation(s);
  mpm_sim_in_boxes(s, w->unit);            /* the units of x_{n+1}; -1: leaving */
  long bad = -1;
  /* the density that decides each point's state (material.state_density),
   * at x_{n+1}, the same over the substeps */
  mpm_material_density_compute(w->dens, NULL, s->cfg.material.state_density, n, P->x, P->y,
                               w->unit, P->mass, P->vol, w->rho);
  if (!w->nl) {                             /* a local model: its update */
#pragma omp parallel for schedule(static) reduction(max : bad)
    for (size_t p = 0; p < n; p++)
      if (!update_local(s, p, w->L + 9 * p, h, w->rho[p]))
        bad = (long)p > bad ? (long)p : bad;
    return bad;
  }
  for (size_t p = 0; p < n; p++) {
    if (w->unit[p] >= 0)
      continue;
    const double x[3] = {P->x[p], P->y[p], P->z[p]};
    if (!mpm_bc3_left_through_outlet(&s->bc3, &s->mesh3, x)) {
      if (mpm_sim_check_state(s, s->t + s->dt, err) != MPM_OK)
        *rc = MPM_ENONFINITE;
      else
        *rc = mpm_err_set(err, MPM_EOUTSIDE, "point %d left the mesh at (%.6g, %.6g, %.6g) m, "
                          "t = %.6g s", P->id[p], P->x[p], P->y[p], P->z[p], s->t + s->dt);
      return -1;
    }
  }
  /* a point out through the open outlet (unit -1) leaves at the step's end
   * (remove.c): it neither enters the unit field nor is updated */
  if (w->extent && (*rc = locate_extents(s, err)) != MPM_OK)
    return -1;
  const int local = s->t < s->par.t_seed - 1e-9 * s->dt;
  const int implicit = s->cfg.material.diffusion == MPM_DIFFUSION_IMPLICIT;
  for (int k = 0; k < s->n_sub; k++) {
#pragma omp parallel for schedule(static)
    for (size_t p = 0; p < n; p++)
      w->dense[p] = (unsigned char)(w->unit[p] >= 0 &&
                                    s->mat->dense(&s->par, stress_of(P, p), w->rho[p]));
    if (w->extent)
      mpm_nonlocal3_average_parts(w->nl, n, w->part, w->pw, P->mass, P->g, w->dense);
    else
      mpm_nonlocal3_average(w->nl, n, w->unit, P->mass, P->g, w->dense);
    if (local)
      memset(w->nl->lap, 0, w->nl->grid.nu * sizeof *w->nl->lap);
    else if (implicit && mpm_nonlocal3_filled(w->nl))
      *rc = mpm_nonlocal3_implicit(w->nl, mpm_material_ngf_diffusivity(&s->par, h), err);
    else
      mpm_nonlocal3_laplacian(w->nl);
    if (*rc != MPM_OK) {
      mpm_err_prefix(err, *rc, "step %ld, t = %.6g s", s->step + 1, s->t + s->dt);
      return -1;
    }
    const double *lap = w->nl->lap;
#pragma omp parallel for schedule(static) reduction(max : bad)
    for (size_t p = 0; p < n; p++) {
      if (w->unit[p] < 0)
        continue;
      const size_t q = MPM_NONLOCAL3_PARTS * p;      /* extent rule: the filled units' mean */
      const double lp = w->extent ? mpm_nonlocal_grid_parts_mean(w->nl->sm, lap, w->part + q,
                                                                 w->pw + q, MPM_NONLOCAL3_PARTS)
                                  : lap[w->unit[p]];
      if (!update_hyper(s, p, w->L + 9 * p, h, lp, w->rho[p]))
        bad = (long)p > bad ? (long)p : bad;
    }
  }
  return bad;
}

/* The open outlet's unit faces become zero-flux faces of the fluidity
 * field: their range, and for a disc the faces inside it unit by unit. */
static int open_field_faces(mpm_sim *s, mpm_err *err)
{
  mpm_nonlocal_grid *g = &s->w3->nl->grid;
  int lo[3], hi[3];
  const int f = mpm_bc3_outlet_faces(&s->bc3, &s->mesh3, lo, hi);
  if (f < 0)
    return MPM_OK;
  mpm_nonlocal_grid_open_faces(g, f, lo, hi);
  if (s->bc3.out_shape != MPM_OUTLET3_DISC)
    return MPM_OK;
  unsigned char *open = calloc(g->nu, 1);
  if (!open)
    return mpm_err_set(err, MPM_ENOMEM, "simulation: no memory for the outlet's unit faces");
  int c[3];
  for (c[2] = lo[2]; c[2] < hi[2]; c[2]++)
    for (c[1] = lo[1]; c[1] < hi[1]; c[1]++)
      for (c[0] = lo[0]; c[0] < hi[0]; c[0]++)
        open[mpm_nonlocal_grid_index(g, c)] =
            (unsigned char)mpm_bc3_outlet_face_open(&s->bc3, &s->mesh3, c);
  free(s->w3->open);
  s->w3->open = open;
  mpm_nonlocal_grid_open_mask(g, open);
  return MPM_OK;
}

int mpm_sim3_step(mpm_sim *s, mpm_err *err)
{
  mpm_points *P = s->pts;
  if (s->cfg.outlet.edge != MPM_OUTLET_NONE && !s->bc3.open &&
      s->t >= s->cfg.outlet.t_open - 1e-9 * s->dt) {
    mpm_bc3_open_outlet(&s->bc3);         /* the orifice opens */
    const int rc = s->w3 && s->w3->nl ? open_field_faces(s, err) : MPM_OK;
    if (rc != MPM_OK)
      return rc;
  }
  int rc = mpm_shape3_stencil_compute(s->st, s->shape3, &s->mesh3, P, s->t, err);
  if (rc == MPM_EOUTSIDE && mpm_sim_check_state(s, s->t, err) != MPM_OK)
    return MPM_ENONFINITE;                /* "outside" at a non-finite position: say that */
  if (rc == MPM_OK && s->cfg.time.transfer == MPM_TRANSFER_APIC && s->shape3->convect)
    rc = mpm_sim_in_apic_extents_fit(s, err);
  if (rc != MPM_OK)
    return rc;
  const int reach = s->st->reach;         /* node layers k - reach .. k + 1 + reach */
  if ((rc = mpm_mesh_bands_sort(s->bands, s->mesh3.nz, s->mesh3.periodic_z, reach, reach + 1,
                                P->n, s->st->row, err)) != MPM_OK)
    return rc;
  double b[3];
  mpm_sim_gravity3(s, s->t, b);
  if (s->usum && (rc = mpm_sim_in_unit_stress(s, err)) != MPM_OK)
    return rc;
  mpm_sim_in_grid3(s, b);
  const long bad = s->w3 ? moved_phase(s, &rc, err) : local_phase(s);
  return rc != MPM_OK ? rc : mpm_sim_in_step_end(s, bad, err);
}
