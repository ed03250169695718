/* step.c: simulation set-up and the explicit Update-Stress-Last MPM step
 * (MODEL.md section 2, [DK15] section 3.1).
 *
 * One step: stencil (once) -> point-to-grid (mass, momentum, force) -> grid
 * update with boundary conditions -> grid-to-point (FLIP velocity, position,
 * velocity gradient) -> volume -> constitutive update -> periodic wrap.
 * The constitutive update runs in n_sub substeps of dt/n_sub with L fixed.
 * A nonlocal model (NGF, [DK-silo] section 5.2) moves the points first, freezes
 * their units, and per substep has nonlocal/ rebuild the element field (the
 * model's dense points, g_e, lap_e by the chosen diffusion solver: field.h)
 * before the point updates (nonlocal_phase); a model with a seeding phase
 * runs as its local model before t_seed, then seeds its field from it
 * (seeding). The step names no model: it asks the material table.
 * The density a point's state is decided with is m / V_{n+1} by default;
 * with material.state_density = "element", "hybrid" ([D-thesis] §3.4) or "unit"
 * all points move first and the unit sums are taken from x_{n+1} before the
 * updates (density_phase, and likewise in nonlocal_phase). V_p always keeps its
 * local update. With mesh.dilatation = "unit" (B-bar, transfer.c) the in-plane
 * mean stress enters point-to-grid as its unit's mean, all points move before
 * tr L_p is replaced by its unit's mean (density_phase or nonlocal_phase), and
 * after the update the dense points of a unit share its mean stress.
 * Threads: the stencil is parallel over points; point-to-grid and the grid
 * update over ranges of nodes (grid_phase); the rest over points
 * (point_phase), except the element sums of g and of mass, which run in
 * point order on one thread. No sum depends on the thread count, so neither do results. */
#include "solver/solver.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scenario/scenario.h"
#include "solver/transfer.h"

#ifdef _OPENMP
#include <omp.h>
#endif

/* ---- set-up -------------------------------------------------------------- */

static int nodal_alloc(mpm_sim *s)
{
  const size_t n = s->mesh.nnodes > 0 ? (size_t)s->mesh.nnodes : 1;
  if (!(s->nm = calloc(n, sizeof *s->nm)))
    return MPM_ENOMEM;
  /* records of four doubles on 32-byte boundaries: one vector each */
  if (!(s->nq = aligned_alloc(32, n * sizeof *s->nq)))
    return MPM_ENOMEM;
  memset(s->nq, 0, n * sizeof *s->nq);
  return MPM_OK;
}

/* dt = cfl min(dx, dy) / (c_p + |v|max) at the densest, fastest fill. */
static double stable_dt(const mpm_config *cfg, const mpm_material_params *par, double cfl)
{
  double rho = 0.0, vmax = 0.0;
  for (int f = 0; f < cfg->nfill; f++) {
    const mpm_fill_config *fc = &cfg->fill[f];
    if (fc->density > rho) rho = fc->density;
    double v = hypot(hypot(fc->vx, fc->vy), fc->vz);
    if (v > vmax) vmax = v;
  }
  double h = fmin(cfg->mesh.dx, cfg->mesh.dy);
  if (cfg->mesh.nz > 0)
    h = fmin(h, cfg->mesh.dz);
  return cfl * h / (mpm_material_wave_speed(par, rho) + vmax);
}

double mpm_sim_stable_dt(const mpm_config *cfg)
{
  mpm_material_params par;
  mpm_material_params_from_config(&par, cfg);
  return stable_dt(cfg, &par, 1.0);
}

double mpm_sim_substeps(const mpm_config *cfg, double dt)
{
  if (!(cfg->material.dt_sub > 0.0))
    return cfg->material.n_sub > 0 ? cfg->material.n_sub : 1;
  double n = ceil(dt / cfg->material.dt_sub * (1.0 - 1e-12));  /* dt/n_sub <= dt_sub */
  return n < 1.0 ? 1.0 : n;
}

void mpm_sim_time_plan(const mpm_config *cfg, double *dt, int *n_sub)
{
  mpm_material_params par;
  mpm_material_params_from_config(&par, cfg);
  *dt = cfg->time.dt > 0.0 ? cfg->time.dt : stable_dt(cfg, &par, cfg->time.cfl);
  double n = mpm_sim_substeps(cfg, *dt);
  *n_sub = n > 1e6 ? 1000000 : (int)n;          /* more is refused before a run is built */
}

/* Per-point L storage for the phases that move every point before any
 * update (nonlocal models, element and hybrid densities); once per run. */
static int L_alloc(mpm_sim *s, mpm_err *err)
{
  if (s->lxx)
    return MPM_OK;
  size_t n = s->pts->cap > 0 ? s->pts->cap : 1;
  double **arrs[] = {&s->lxx, &s->lxy, &s->lyx, &s->lyy};
  for (size_t k = 0; k < 4; k++)
    if (!(*arrs[k] = calloc(n, sizeof(double))))
      return mpm_err_set(err, MPM_ENOMEM, "simulation: no memory for %zu velocity gradients", n);
  s->lcap = n;
  return MPM_OK;
}

/* Per-point L storage and the nonlocal workspace for models that need them. */
static int nonlocal_alloc(mpm_sim *s, mpm_err *err)
{
  if (!s->mat->nonlocal)
    return MPM_OK;
  const mpm_config *cfg = &s->cfg;
  int edge[4] = {cfg->bc.left, cfg->bc.right, cfg->bc.bottom, cfg->bc.top};
  int rc = mpm_nonlocal_alloc(&s->nl, &s->mesh, edge, cfg->material.g_average, s->pts->cap, err);
  if (rc == MPM_OK)
    rc = mpm_nonlocal_set_diffusion(s->nl, cfg->material.diffusion, err);
  if (rc != MPM_OK)
    return rc;
  if (cfg->material.g_wall == MPM_NONLOCAL_WALL_NEUMANN)
    mpm_nonlocal_walls_neumann(s->nl);
  if (mpm_nonlocal_is_steady(s->nl)) {     /* g from the stress each step: nothing to seed */
    if (!s->mat->steady_terms || !s->mat->update_steady_plane)
      return mpm_err_set(err, MPM_EINPUT, "material.diffusion = \"steady\": model '%s' has no "
                         "steady form", s->mat->name);
    s->seeded = 1;
  }
  return L_alloc(s, err);
}

/* Per-point density and the unit sums for the element, hybrid and unit rules (the
 * point rule reads m / V directly and needs neither). The per-point L arrays
 * hold the velocity gradients between moving the points and updating them. */
static int density_alloc(mpm_sim *s, mpm_err *err)
{
  int rule = s->cfg.material.state_density;
  if (!mpm_material_density_rule_name(rule))
    return mpm_err_set(err, MPM_EINPUT, "material.state_density = %d unknown", rule);
  if (rule == MPM_DENSITY_POINT)
    return MPM_OK;
  int rc = mpm_material_density_alloc(&s->dens, &s->mesh, err);
  if (rc != MPM_OK)
    return rc;
  size_t n = s->pts->cap > 0 ? s->pts->cap : 1;
  if (!(s->rho = malloc(n * sizeof *s->rho)))
    return mpm_err_set(err, MPM_ENOMEM, "simulation: no memory for %zu densities", n);
  s->rcap = n;
  return L_alloc(s, err);
}

/* mpm_sim_create's part for a plane input: mesh, edges, walls, shape,
 * points, nodal records and the workspaces of the options. */
static int build_plane(mpm_sim *s, mpm_err *err)
{
  const mpm_config *cfg = &s->cfg;
  if (s->mat->hyper)
    return mpm_err_set(err, MPM_EINPUT, "material.model '%s' runs in 3D runs only (mesh.nz > 0)",
                       s->mat->name);
  int rc = mpm_mesh_from_config(&s->mesh, cfg, err);
  if (rc == MPM_OK) {
    int edge[4] = {cfg->bc.left, cfg->bc.right, cfg->bc.bottom, cfg->bc.top};
    rc = mpm_bc_setup(&s->bc, &s->mesh, edge, err);
  }
  if (rc == MPM_OK && cfg->outlet.edge != MPM_OUTLET_NONE)
    rc = mpm_bc_set_outlet(&s->bc, &s->mesh, cfg->outlet.edge - MPM_OUTLET_LEFT + MPM_EDGE_LEFT,
                           cfg->outlet.from, cfg->outlet.to, cfg->outlet.closed,
                           cfg->outlet.ends == MPM_OUTLET_ENDS_FIXED, err);
  if (rc == MPM_OK && cfg->wall.nvert > 0)
    rc = mpm_bc_add_polygon(&s->bc, &s->mesh, cfg->wall.nvert, cfg->wall.px, cfg->wall.py,
                            cfg->wall.kind, NULL, err);
  if (rc == MPM_OK && !(s->shape = mpm_shape_lookup(cfg->mesh.shape)))
    rc = mpm_err_set(err, MPM_EINPUT, "mesh.shape '%s' unknown", cfg->mesh.shape);
  if (rc == MPM_OK && !(s->pts = mpm_points_alloc(1024)))
    rc = mpm_err_set(err, MPM_ENOMEM, "points: out of memory");
  for (int f = 0; rc == MPM_OK && f < cfg->nfill; f++)
    rc = mpm_scenario_fill(s->pts, &s->mesh, &cfg->fill[f], &s->par, cfg->gravity.gy, err);
  if (rc == MPM_OK && (nodal_alloc(s) != MPM_OK || !(s->st = mpm_shape_stencil_alloc(0)) ||
                       !(s->bands = mpm_mesh_bands_alloc())))
    rc = mpm_err_set(err, MPM_ENOMEM, "simulation workspace: out of memory");
  if (rc == MPM_OK)
    s->located = s->shape->at_point;
  if (rc == MPM_OK)
    rc = nonlocal_alloc(s, err);
  if (rc == MPM_OK)
    rc = density_alloc(s, err);
  const size_t nu = (size_t)s->mesh.nx * (size_t)s->mesh.ny;
  if (rc == MPM_OK && cfg->mesh.dilatation != MPM_DILATATION_POINT &&
      (!(s->usum = malloc(2 * nu * sizeof *s->usum)) ||
       (cfg->mesh.dilatation == MPM_DILATATION_ELEMENT &&
        !(s->uel = calloc(mpm_sim_in_el_width(s) * nu, sizeof *s->uel)))))
    rc = mpm_err_set(err, MPM_ENOMEM, "simulation: no memory for the unit sums");
  return rc;
}

int mpm_sim_create(mpm_sim **out, const mpm_config *cfg, mpm_err *err)
{
  *out = NULL;
  mpm_sim *s = calloc(1, sizeof *s);
  if (!s)
    return mpm_err_set(err, MPM_ENOMEM, "simulation: out of memory");
  s->cfg = *cfg;
  s->scan = MPM_SIM_SCAN_ALL;
  s->dim = cfg->mesh.nz > 0 ? 3 : 2;
  int rc = MPM_OK;
  if (!(s->mat = mpm_material_lookup(cfg->material.model)))
    rc = mpm_err_set(err, MPM_EINPUT, "material.model '%s' unknown", cfg->material.model);
  if (rc == MPM_OK) {
    mpm_material_params_from_config(&s->par, cfg);
    rc = s->mat->check(&s->par, err);
  }
  if (rc == MPM_OK)
    rc = s->dim == 3 ? mpm_sim3_build(s, err) : build_plane(s, err);
  if (rc == MPM_OK && s->pts->n == 0)
    rc = mpm_err_set(err, MPM_EINPUT, "the fills hold no point");
  if (rc == MPM_OK && cfg->time.transfer == MPM_TRANSFER_APIC)
    rc = mpm_sim_in_node_table(s, err);       /* the offsets x_i - x_p */
  if (rc != MPM_OK) {
    mpm_sim_free(s);
    return rc;
  }
  mpm_sim_time_plan(cfg, &s->dt, &s->n_sub);
  for (size_t p = 0; p < s->pts->n; p++)
    s->mass0 += s->pts->mass[p];
  s->mtiny = 1e-12 * s->mass0 / (double)s->pts->n;          /* skip nodes lighter than this */
  if (s->dim == 3 ? s->shape3->at_point : s->shape->at_point) {  /* body force only below this */
    s->mlight = 1e-3 * s->mass0 / (double)s->pts->n;
    double mmin = s->pts->mass[0];
    for (size_t p = 1; p < s->pts->n; p++)
      mmin = fmin(mmin, s->pts->mass[p]);
    s->stiny = s->mtiny / mmin;  /* m_i >= S_ip m_p: empty only if S_ip <= stiny */
  }
  *out = s;
  return MPM_OK;
}

void mpm_sim_free(mpm_sim *s)
{
  if (!s)
    return;
  mpm_bc_clear(&s->bc);
  mpm_bc3_clear(&s->bc3);
  mpm_points_free(s->pts);
  mpm_shape_stencil_free(s->st);
  mpm_mesh_bands_free(s->bands);
  mpm_nonlocal_free(s->nl);
  mpm_material_density_free(s->dens);
  free(s->rho);
  free(s->usum);
  free(s->uel);
  free(s->uof);
  free(s->xnode);
  free(s->lxx);
  free(s->lxy);
  free(s->lyx);
  free(s->lyy);
  free(s->loc_i);
  free(s->loc_j);
  free(s->loc_n);
  free(s->loc_u);
  free(s->loc_v);
  free(s->scratch);
  free(s->nm);
  free(s->nq);
  free(s->nq3);
  mpm_sim3_work_free(s->w3);
  free(s);
}

void mpm_sim_gravity3(const mpm_sim *s, double t, double g[3])
{
  double r = s->cfg.gravity.t_ramp;
  double f = (r > 0.0 && t < r) ? t / r : 1.0;             /* linear ramp 0 -> 1 over t_ramp */
  g[0] = f * s->cfg.gravity.gx;
  g[1] = f * s->cfg.gravity.gy;
  g[2] = f * s->cfg.gravity.gz;
}

void mpm_sim_gravity(const mpm_sim *s, double t, double *gx, double *gy)
{
  double g[3];
  mpm_sim_gravity3(s, t, g);
  *gx = g[0];
  *gy = g[1];
}

/* ---- the step ------------------------------------------------------------ */

/* The points are moved and updated in chunks: grid-to-point for the chunk
 * (its velocity gradients and grid velocities kept here), then the model's
 * update of the whole chunk at once (mpm_material_batch), then step 7. */
enum { CHUNK = 64 };

typedef struct chunk {
  double lxx[CHUNK], lxy[CHUNK], lyx[CHUNK], lyy[CHUNK];  /* L_p */
  double rho[CHUNK], lap[CHUNK], isp[CHUNK];             /* the update's inputs */
  double vgx[CHUNK], vgy[CHUNK];                         /* grid velocity that moves p */
  double agx[CHUNK], agy[CHUNK];                         /* grid acceleration at p */
} chunk;

/* Steps 4-5 for points [a, b): L_p to lxx[p - a] ..., the grid velocity
 * that moved point p to ck->vgx[p - a], ck->vgy[p - a]; with APIC (apic
 * 1), L_p is also the point's affine matrix C_p for the next step, its
 * empty nodes taking the point's velocity (mpm_sim_in_affine). */
static inline void g2p_range(mpm_sim *s, size_t a, size_t b, int kind, int apic, double *lxx,
                             double *lxy, double *lyx, double *lyy, chunk *ck)
{
  for (size_t p = a; p < b; p++) {
    mpm_sim_in_basis buf;
    const int *node;
    const double *S, *gx, *gy;
    double L[4], vg[2], ag[2];
    const int c = mpm_sim_in_weights(s, p, kind, &buf, &node, &S, &gx, &gy);
    mpm_sim_in_gather(s, c, node, S, gx, gy, vg, ag, L);
    if (apic) {                               /* C_p = sum v_i (x) gradS_ip */
      mpm_sim_in_affine(s, c, node, S, gx, gy, vg, L);
      s->pts->cxx[p] = L[0];
      s->pts->cxy[p] = L[1];
      s->pts->cyx[p] = L[2];
      s->pts->cyy[p] = L[3];
    }
    lxx[p - a] = L[0];
    lxy[p - a] = L[1];
    lyx[p - a] = L[2];
    lyy[p - a] = L[3];
    ck->vgx[p - a] = vg[0];
    ck->vgy[p - a] = vg[1];
    ck->agx[p - a] = ag[0];
    ck->agy[p - a] = ag[1];
  }
  mpm_sim_in_advance(s, a, b, ck->vgx, ck->vgy, ck->agx, ck->agy, lxx, lxy, lyx, lyy);
}

/* Steps 4-5 for points [a, b) with the weights of the step; see g2p_range,
 * compiled once per kind of weights and transfer. */
static void move_range(mpm_sim *s, size_t a, size_t b, double *lxx, double *lxy, double *lyx,
                       double *lyy, chunk *ck)
{
  const int apic = s->cfg.time.transfer == MPM_TRANSFER_APIC;
  switch (mpm_sim_in_kind(s)) {
  case MPM_SIM_IN_Q4:
    if (apic)
      g2p_range(s, a, b, MPM_SIM_IN_Q4, 1, lxx, lxy, lyx, lyy, ck);
    else
      g2p_range(s, a, b, MPM_SIM_IN_Q4, 0, lxx, lxy, lyx, lyy, ck);
    break;
  case MPM_SIM_IN_ELEMENT:
    if (apic)
      g2p_range(s, a, b, MPM_SIM_IN_ELEMENT, 1, lxx, lxy, lyx, lyy, ck);
    else
      g2p_range(s, a, b, MPM_SIM_IN_ELEMENT, 0, lxx, lxy, lyx, lyy, ck);
    break;
  default:
    if (apic)
      g2p_range(s, a, b, MPM_SIM_IN_STORED, 1, lxx, lxy, lyx, lyy, ck);
    else
      g2p_range(s, a, b, MPM_SIM_IN_STORED, 0, lxx, lxy, lyx, lyy, ck);
  }
}

/* Step 6 for points [a, b): n substeps of length h of the update of model
 * mat (update_steady instead when steady) with L fixed; rho, lap, isp as in
 * mpm_material_batch. Returns the largest index of a point whose stress
 * became non-finite, or -1. */
static long update_range(mpm_sim *s, const mpm_material_type *mat, int steady, size_t a, size_t b,
                         const double *lxx, const double *lxy, const double *lyx,
                         const double *lyy, const double *rho, const double *lap,
                         const double *isp, double h, int n)
{
  mpm_points *P = s->pts;
  const mpm_material_batch bt = {
    .n = b - a, .lxx = lxx, .lxy = lxy, .lyx = lyx, .lyy = lyy, .rho = rho, .lap = lap,
    .isp = isp, .sxx = P->sxx + a, .syy = P->syy + a, .szz = P->szz + a, .sxy = P->sxy + a,
    .g = P->g + a, .gdp = P->gdp + a, .state = P->state + a,
  };
  if (steady)
    mat->update_steady_plane(&s->par, h, n, &bt);
  else
    mat->update_plane(&s->par, h, n, &bt);
  long bad = -1;
  for (size_t p = a; p < b; p++)
    if (!isfinite(P->sxx[p] + P->syy[p] + P->szz[p] + P->sxy[p]))
      bad = (long)p;
  return bad;
}

/* rho_{n+1} of points [a, b) for their update: the density computed for
 * the step (element, hybrid or unit rule, [D-thesis] §3.4) or m / V_{n+1}. */
static const double *state_rho(const mpm_sim *s, size_t a, size_t b, double *buf)
{
  if (s->dens)
    return s->rho + a;
  for (size_t p = a; p < b; p++)
    buf[p - a] = s->pts->mass[p] / s->pts->vol[p];               /* rho_{n+1} = m / V */
  return buf;
}

/* What the end of the step will ask of points [a, b), asked while they are
 * at hand (mpm_sim.scan): whether one may leave, whether one is too fast. */
static inline unsigned moved_scan(const mpm_sim *s, size_t a, size_t b)
{
  return (mpm_sim_may_leave(s, a, b) ? MPM_SIM_SCAN_LEAVE : 0u) |
         (mpm_sim_too_fast(s, a, b) ? MPM_SIM_SCAN_FAST : 0u);
}

/* Steps 4-7 chunk by chunk for a local model (once the grid is known the
 * points are independent): grid-to-point, the update in n_sub substeps,
 * bookkeeping. Returns the largest index of a point whose stress became
 * non-finite, or -1. */
static long point_phase(mpm_sim *s, const mpm_material_type *mat)
{
  const size_t n = s->pts->n, nc = (n + CHUNK - 1) / CHUNK;
  const double h = s->dt / s->n_sub;
  long bad = -1;
  unsigned scan = 0;
#pragma omp parallel for schedule(static) reduction(max : bad) reduction(| : scan)
  for (size_t c = 0; c < nc; c++) {
    chunk ck;
    const size_t a = c * CHUNK, b = a + CHUNK < n ? a + CHUNK : n;
    move_range(s, a, b, ck.lxx, ck.lxy, ck.lyx, ck.lyy, &ck);
    long bc = update_range(s, mat, 0, a, b, ck.lxx, ck.lxy, ck.lyx, ck.lyy,
                           state_rho(s, a, b, ck.rho), NULL, NULL, h, s->n_sub);
    bad = bc > bad ? bc : bad;
    mpm_sim_in_bookkeeping(s, a, b, ck.vgx, ck.vgy);
    scan |= moved_scan(s, a, b);
  }
  s->scan = scan;
  return bad;
}

/* Element, hybrid or unit density of every point from x_{n+1}, V_{n+1};
 * unit: the points' units of x_{n+1} when already found (NULL: found here). */
static void update_density(mpm_sim *s, const int *unit)
{
  const mpm_points *P = s->pts;
  if (s->dens)
    mpm_material_density_compute(s->dens, &s->mesh, s->cfg.material.state_density, P->n, P->x,
                                 P->y, unit, P->mass, P->vol, s->rho);
}

/* Grow the per-point L arrays (and densities) with the point store. */
static int reserve_L(mpm_sim *s, mpm_err *err)
{
  size_t n = s->pts->n;
  if (s->dens && n > s->rcap) {
    double *r = realloc(s->rho, n * sizeof *r);
    if (!r)
      return mpm_err_set(err, MPM_ENOMEM, "simulation: no memory for %zu densities", n);
    s->rho = r;
    s->rcap = n;
  }
  if (n <= s->lcap)
    return MPM_OK;
  double **arrs[] = {&s->lxx, &s->lxy, &s->lyx, &s->lyy};
  for (size_t k = 0; k < 4; k++) {
    double *a = realloc(*arrs[k], n * sizeof(double));
    if (!a)
      return mpm_err_set(err, MPM_ENOMEM, "simulation: no memory for %zu velocity gradients", n);
    *arrs[k] = a;
  }
  s->lcap = n;
  return MPM_OK;
}

/* Steps 4, 5 and 7 for every point before any constitutive update (models
 * whose update needs all points at x_{n+1}): grid-to-point, L_p stored for
 * the update, walls and periodic wrap. */
static int move_points(mpm_sim *s, mpm_err *err)
{
  const size_t n = s->pts->n, nc = (n + CHUNK - 1) / CHUNK;
  int rc = reserve_L(s, err);
  if (rc != MPM_OK)
    return rc;
  unsigned scan = 0;
#pragma omp parallel for schedule(static) reduction(| : scan)
  for (size_t c = 0; c < nc; c++) {
    chunk ck;
    const size_t a = c * CHUNK, b = a + CHUNK < n ? a + CHUNK : n;
    move_range(s, a, b, s->lxx + a, s->lxy + a, s->lyx + a, s->lyy + a, &ck);
    mpm_sim_in_bookkeeping(s, a, b, ck.vgx, ck.vgy);
    scan |= moved_scan(s, a, b);
  }
  s->scan = scan;
  if (s->usum)                               /* B-bar: tr L_p and V_p per unit */
    mpm_sim_in_unit_dilatation(s);
  return MPM_OK;
}

/* Step 6 chunk by chunk with the stored L_p (after move_points); nonlocal:
 * each point's lap and isp from the field of the (sub)step. */
static long update_stored(mpm_sim *s, const mpm_material_type *mat, int steady, int nonlocal,
                          int n_sub)
{
  const size_t n = s->pts->n, nc = (n + CHUNK - 1) / CHUNK;
  const double h = s->dt / s->n_sub;
  long bad = -1;
#pragma omp parallel for schedule(static) reduction(max : bad)
  for (size_t c = 0; c < nc; c++) {
    chunk ck;
    const size_t a = c * CHUNK, b = a + CHUNK < n ? a + CHUNK : n;
    if (nonlocal)
      for (size_t p = a; p < b; p++) {
        ck.lap[p - a] = mpm_nonlocal_point_lap(s->nl, p);
        ck.isp[p - a] = mpm_nonlocal_point_isp(s->nl, p);
      }
    long bc = update_range(s, mat, steady, a, b, s->lxx + a, s->lxy + a, s->lyx + a, s->lyy + a,
                           state_rho(s, a, b, ck.rho), nonlocal ? ck.lap : NULL,
                           nonlocal ? ck.isp : NULL, h, n_sub);
    bad = bc > bad ? bc : bad;
  }
  return bad;
}

/* Point-to-unit membership for the step, from the positions x_{n+1} (and,
 * under the extent rule, the point extents); a point outside the mesh is an
 * error naming its id, position and time. */
static int locate(mpm_sim *s, mpm_err *err)
{
  const mpm_points *P = s->pts;
  const double *const r[4] = {P->r1x, P->r1y, P->r2x, P->r2y};
  int rc = mpm_nonlocal_locate_extents(s->nl, &s->mesh, P->n, P->x, P->y, r, err);
  if (rc != MPM_EOUTSIDE)
    return rc;
  for (size_t p = 0; p < P->n; p++) {
    int i, j;
    if (mpm_mesh_unit(&s->mesh, P->x[p], P->y[p], &i, &j) != MPM_OK)
      return mpm_err_set(err, MPM_EOUTSIDE, "point %d left the mesh at (%.6g, %.6g) m, t = %.6g s",
                         P->id[p], P->x[p], P->y[p], s->t + s->dt);
  }
  return rc;
}

/* Steps 4-7 for a nonlocal model ([DK-silo] section 5.2; MODEL.md section 5):
 * grid-to-point and bookkeeping first (L_p stored), membership frozen, then
 * per substep: dense flags, element g (summed in point order: no dependence on
 * the thread count), its Laplacian, and the point updates with lap_e.
 * With the steady solver (MODEL.md section 6, [D-thesis] Algorithm 2) the
 * field is solved once, before the points move: from the stress at the start
 * of the step, on the nodes of the step's stencil, each point's g set to
 * what it reads there; the substeps then run the model's update_steady. */
static long nonlocal_phase(mpm_sim *s, int *rc, mpm_err *err)
{
  mpm_points *P = s->pts;
  mpm_nonlocal *nl = s->nl;
  const double h = s->dt / s->n_sub;
  const int steady = mpm_nonlocal_is_steady(nl);
  if (steady && s->located &&                /* the steady solve reads a stored stencil */
      (*rc = mpm_shape_stencil_compute(s->st, s->shape, &s->mesh, P, s->t, err)) != MPM_OK)
    return -1;
  if (steady && (*rc = mpm_nonlocal_steady_field(nl, s->mat, &s->par, P, s->st, &s->mesh,
                                                 s->cfg.material.g_sample,
                                                 s->cfg.material.g_mass, err)) != MPM_OK) {
    mpm_err_prefix(err, *rc, "step %ld, t = %.6g s", s->step + 1, s->t);
    return -1;
  }
  if ((*rc = move_points(s, err)) != MPM_OK)
    return -1;
  /* Points leaving through an outlet go before the units are frozen: outside
   * the mesh they have no unit. */
  if ((*rc = mpm_sim_remove_points(s, s->t + s->dt, err)) != MPM_OK || (*rc = locate(s, err)) != MPM_OK)
    return -1;
  update_density(s, nl->unit);  /* the units just frozen */
  if (steady)                                /* g given: the substeps with L fixed */
    return update_stored(s, s->mat, 1, 0, s->n_sub);
  long bad = -1;
  for (int k = 0; k < s->n_sub; k++) {
    *rc = mpm_nonlocal_field(nl, s->mat, &s->par, P, s->dens ? s->rho : NULL, h, err);
    if (*rc != MPM_OK) {                     /* g_e, lap_e, isp_e of the dense points */
      mpm_err_prefix(err, *rc, "step %ld, t = %.6g s", s->step + 1, s->t + s->dt);
      return -1;
    }
    long b = update_stored(s, s->mat, 0, 1, 1);
    bad = b > bad ? b : bad;
  }
  return bad;
}

/* Steps 4-7 for a local model with the element, hybrid or unit density or
 * the B-bar dilatation: the density of a unit needs every point at x_{n+1},
 * and the unit's divergence every point's L_p, so all points move first (L_p
 * stored, walls and periodic wrap applied), then the unit sums run in point
 * order and the points are updated. Returns as point_phase. */
static long density_phase(mpm_sim *s, const mpm_material_type *mat, int *rc, mpm_err *err)
{
  if ((*rc = move_points(s, err)) != MPM_OK || (*rc = mpm_sim_in_units_moved(s, err)) != MPM_OK)
    return -1;
  update_density(s, s->uof);                 /* the projection reuses the units */
  return update_stored(s, mat, 0, 0, s->n_sub);
}

/* Seeding ([DK-silo] section 6, for NGF: g = 0 is always a solution): a
 * model with a seeding phase runs as its local model while t < t_seed, then
 * sets the field of each dense point from that run (g = gdot_p / mu).
 * Returns the model for this step. */
static const mpm_material_type *seeding(mpm_sim *s)
{
  if (!s->mat->before_seed || s->seeded)
    return s->mat;
  if (s->t < s->par.t_seed - 1e-9 * s->dt)
    return s->mat->before_seed;
  mpm_points *P = s->pts;
  for (size_t p = 0; p < P->n; p++) {
    P->g[p] = P->state[p] == MPM_STATE_DENSE ? s->mat->seed(mpm_points_stress(P, p), P->gdp[p])
                                              : 0.0;
  }
  s->seeded = 1;
  return s->mat;
}

/* One step (see mpm_sim_step). */
static int step(mpm_sim *s, mpm_err *err)
{
  int rc = mpm_sim_in_weights_all(s, err);
  if (rc != MPM_OK)
    return rc;
  if (s->cfg.outlet.edge != MPM_OUTLET_NONE && !s->bc.open &&
      s->t >= s->cfg.outlet.t_open - 1e-9 * s->dt) {
    mpm_bc_open_outlet(&s->bc);                              /* the orifice opens */
    if (s->nl) {                                             /* a free surface for g */
      int lo, hi;
      const int e = mpm_bc_outlet_faces(&s->bc, &s->mesh, &lo, &hi);
      mpm_nonlocal_open_faces(s->nl, e, lo, hi);
    }
  }
  double bx, by;
  mpm_sim_gravity(s, s->t, &bx, &by);
  if (s->usum && (rc = mpm_sim_in_unit_stress(s, err)) != MPM_OK)
    return rc;
  mpm_sim_in_grid(s, bx, by);
  const mpm_material_type *mat = seeding(s);
  long bad;
  if (mat->nonlocal) {
    bad = nonlocal_phase(s, &rc, err);
    if (rc != MPM_OK)
      return rc;
  } else if (s->dens || s->usum) {
    bad = density_phase(s, mat, &rc, err);
    if (rc != MPM_OK)
      return rc;
  } else {
    bad = point_phase(s, mat);
  }
  return mpm_sim_in_step_end(s, bad, err);
}

int mpm_sim_in_step_end(mpm_sim *s, long bad, mpm_err *err)
{
  if (bad >= 0)                              /* a non-finite stress: what, where, why */
    return mpm_sim_check_state(s, s->t + s->dt, err);
  if (s->usum)                               /* one mean stress per unit */
    mpm_sim_in_unit_project(s);
  s->t += s->dt;
  s->step++;
  const int rc = mpm_sim_check_speeds(s, s->t, err);
  return rc != MPM_OK ? rc : mpm_sim_remove_points(s, s->t, err);
}

int mpm_sim_step(mpm_sim *s, mpm_err *err)
{
  const int rc = s->dim == 3 ? mpm_sim3_step(s, err) : step(s, err);
  s->scan = MPM_SIM_SCAN_ALL;                /* outside a step nothing is known */
  return rc;
}
