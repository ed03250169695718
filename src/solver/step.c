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
 * local update (with mesh.dilatation = "unit", from the unit's B-bar divergence).
 * Threads: the stencil is parallel over points; point-to-grid and the grid
 * update over ranges of nodes (grid_phase); the rest over points
 * (point_phase), except the element sums of g and of mass, which run in
 * point order on one thread. No sum depends on the thread count, so neither do results. */
#include "solver/solver.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scenario/scenario.h"

#ifdef _OPENMP
#include <omp.h>
#endif

/* ---- set-up -------------------------------------------------------------- */

static int nodal_alloc(mpm_sim *s)
{
  size_t n = (size_t)s->mesh.nnodes;
  double **arrs[] = {&s->nm, &s->nmvx, &s->nmvy, &s->nfx, &s->nfy,
                     &s->nvx, &s->nvy, &s->nax, &s->nay};
  for (size_t k = 0; k < sizeof arrs / sizeof arrs[0]; k++)
    if (!(*arrs[k] = calloc(n, sizeof(double))))
      return MPM_ENOMEM;
  if (!(s->nbusy = calloc(n + 1, sizeof *s->nbusy)))
    return MPM_ENOMEM;
  return MPM_OK;
}

/* dt = cfl min(dx, dy) / (c_p + |v|max) at the densest, fastest fill. */
static double stable_dt(const mpm_config *cfg, const mpm_material_params *par, double cfl)
{
  double rho = 0.0, vmax = 0.0;
  for (int f = 0; f < cfg->nfill; f++) {
    const mpm_fill_config *fc = &cfg->fill[f];
    if (fc->density > rho) rho = fc->density;
    double v = hypot(fc->vx, fc->vy);
    if (v > vmax) vmax = v;
  }
  double h = fmin(cfg->mesh.dx, cfg->mesh.dy);
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
    if (!s->mat->steady_terms || !s->mat->update_steady)
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

int mpm_sim_create(mpm_sim **out, const mpm_config *cfg, mpm_err *err)
{
  *out = NULL;
  mpm_sim *s = calloc(1, sizeof *s);
  if (!s)
    return mpm_err_set(err, MPM_ENOMEM, "simulation: out of memory");
  s->cfg = *cfg;
  int rc = mpm_mesh_from_config(&s->mesh, cfg, err);
  if (rc == MPM_OK) {
    int edge[4] = {cfg->bc.left, cfg->bc.right, cfg->bc.bottom, cfg->bc.top};
    rc = mpm_bc_setup(&s->bc, &s->mesh, edge, err);
  }
  if (rc == MPM_OK && cfg->outlet.edge != MPM_OUTLET_NONE)
    rc = mpm_bc_set_outlet(&s->bc, &s->mesh, cfg->outlet.edge - MPM_OUTLET_LEFT + MPM_EDGE_LEFT,
                           cfg->outlet.from, cfg->outlet.to, cfg->outlet.closed, err);
  if (rc == MPM_OK && cfg->wall.nvert > 0)
    rc = mpm_bc_add_polygon(&s->bc, &s->mesh, cfg->wall.nvert, cfg->wall.px, cfg->wall.py,
                            cfg->wall.kind, NULL, err);
  if (rc == MPM_OK && !(s->shape = mpm_shape_lookup(cfg->mesh.shape)))
    rc = mpm_err_set(err, MPM_EINPUT, "mesh.shape '%s' unknown", cfg->mesh.shape);
  if (rc == MPM_OK && !(s->mat = mpm_material_lookup(cfg->material.model)))
    rc = mpm_err_set(err, MPM_EINPUT, "material.model '%s' unknown", cfg->material.model);
  if (rc == MPM_OK) {
    mpm_material_params_from_config(&s->par, cfg);
    rc = s->mat->check(&s->par, err);
  }
  if (rc == MPM_OK && !(s->pts = mpm_points_alloc(1024)))
    rc = mpm_err_set(err, MPM_ENOMEM, "points: out of memory");
  for (int f = 0; rc == MPM_OK && f < cfg->nfill; f++)
    rc = mpm_scenario_fill(s->pts, &s->mesh, &cfg->fill[f], &s->par, cfg->gravity.gy, err);
  if (rc == MPM_OK && (nodal_alloc(s) != MPM_OK || !(s->st = mpm_shape_stencil_alloc(s->pts->cap))))
    rc = mpm_err_set(err, MPM_ENOMEM, "simulation workspace: out of memory");
  if (rc == MPM_OK)
    rc = nonlocal_alloc(s, err);
  if (rc == MPM_OK)
    rc = density_alloc(s, err);
  if (rc == MPM_OK && cfg->mesh.dilatation == MPM_DILATATION_UNIT &&
      !(s->ug = malloc(9 * (size_t)s->mesh.nx * (size_t)s->mesh.ny * sizeof *s->ug)))
    rc = mpm_err_set(err, MPM_ENOMEM, "simulation: no memory for the unit gradients");
  if (rc != MPM_OK) {
    mpm_sim_free(s);
    return rc;
  }
  mpm_sim_time_plan(cfg, &s->dt, &s->n_sub);
  for (size_t p = 0; p < s->pts->n; p++)
    s->mass0 += s->pts->mass[p];
  s->mtiny = 1e-12 * s->mass0 / (double)s->pts->n;          /* skip nodes lighter than this */
  if (s->shape == &mpm_shape_delta)                          /* body force only below this */
    s->mlight = 1e-3 * s->mass0 / (double)s->pts->n;
  *out = s;
  return MPM_OK;
}

void mpm_sim_free(mpm_sim *s)
{
  if (!s)
    return;
  mpm_bc_clear(&s->bc);
  mpm_points_free(s->pts);
  mpm_shape_stencil_free(s->st);
  free(s->nbusy);
  mpm_nonlocal_free(s->nl);
  mpm_material_density_free(s->dens);
  free(s->rho);
  free(s->ug);
  free(s->uof);
  free(s->lxx);
  free(s->lxy);
  free(s->lyx);
  free(s->lyy);
  double *arrs[] = {s->nm, s->nmvx, s->nmvy, s->nfx, s->nfy, s->nvx, s->nvy,
                    s->nax, s->nay};
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

/* Point-to-grid and the grid update run in parallel over disjoint ranges of
 * storage node ids. The thread owning [lo, hi) visits every point in point
 * order and adds only the contributions to its own nodes, so each node sums
 * its contributions in point order, exactly as a serial loop does: nodal
 * values, and so the whole step, are bitwise independent of the number of
 * threads and of where the ranges are cut. The cuts only balance the work:
 * each range gets about the same number of nodes that carried mass in the
 * previous step (nbusy[i] counts those among nodes [0, i)). */

/* nbusy[i] = number of nodes among [0, i) heavier than mtiny. */
static void count_busy_nodes(mpm_sim *s)
{
  int busy = 0;
  for (int i = 0; i < s->mesh.nnodes; i++) {
    s->nbusy[i] = busy;
    busy += s->nm[i] > s->mtiny;
  }
  s->nbusy[s->mesh.nnodes] = busy;
}

/* First node of range t of nt: the first i >= 1 with nbusy[i] >= busy t / nt
 * (so about t / nt of the nodes with mass lie before it), or an even split of
 * the node ids while no node carries mass. */
static int range_start(const mpm_sim *s, int t, int nt)
{
  const int nn = s->mesh.nnodes;
  const long long busy = s->nbusy[nn];
  if (t == 0 || t == nt)
    return t == 0 ? 0 : nn;
  if (busy == 0)
    return (int)((long long)nn * t / nt);
  const long long want = busy * t / nt;
  int a = 0, b = nn;                       /* nbusy[a] < want <= nbusy[b] */
  while (b - a > 1) {
    const int c = a + (b - a) / 2;
    if (s->nbusy[c] < want)
      a = c;
    else
      b = c;
  }
  return b;
}

/* B-bar weights of the step ([mesh] dilatation = "unit", delta weights on q4,
 * so a point's stencil is the corners of its unit in mpm_mesh_basis order):
 * per unit u, ug[9u] = sum V_p over its points and ug[9u + 1 + k],
 * ug[9u + 5 + k] the volume-weighted mean of their dS_k/dx, dS_k/dy. The
 * points are the unit's quadrature: four points placed symmetrically give the
 * gradient at the unit centre, one point its own gradient (the point rule),
 * so a node the points barely reach gets no more force than without B-bar.
 * Sums in point order on one thread: thread-count free. */
static int unit_gradients(mpm_sim *s, mpm_err *err)
{
  const mpm_points *P = s->pts;
  const mpm_shape_stencil *st = s->st;
  const size_t nu = (size_t)s->mesh.nx * (size_t)s->mesh.ny;
  if (P->n > s->ucap) {
    long *u = realloc(s->uof, P->n * sizeof *u);
    if (!u)
      return mpm_err_set(err, MPM_ENOMEM, "simulation: no memory for %zu point units", P->n);
    s->uof = u;
    s->ucap = P->n;
  }
  memset(s->ug, 0, 9 * nu * sizeof *s->ug);
  for (size_t p = 0; p < P->n; p++) {
    int i, j;
    s->uof[p] = -1;
    if (mpm_mesh_unit(&s->mesh, P->x[p], P->y[p], &i, &j) != MPM_OK)
      continue;
    s->uof[p] = (long)i + (long)s->mesh.nx * j;
    double *u = s->ug + 9 * s->uof[p];
    const double V = P->vol[p];
    const double *gx = st->dSx + p * MPM_STENCIL_W, *gy = st->dSy + p * MPM_STENCIL_W;
    u[0] += V;
    for (int k = 0; k < 4; k++) {
      u[1 + k] += V * gx[k];
      u[5 + k] += V * gy[k];
    }
  }
  for (size_t e = 0; e < nu; e++) {
    double *u = s->ug + 9 * e;
    if (u[0] > 0.0)
      for (int k = 1; k < 9; k++)
        u[k] /= u[0];
  }
  return MPM_OK;
}

/* The B-bar gradients of point p's unit: dS_k/dx at gx[0..3], dS_k/dy at
 * gy[0..3] (its own gradients when it is outside the mesh). */
static void bbar_gradient(const mpm_sim *s, size_t p, const double **gx, const double **gy)
{
  if (s->uof[p] < 0) {
    *gx = s->st->dSx + p * MPM_STENCIL_W;
    *gy = s->st->dSy + p * MPM_STENCIL_W;
  } else {
    *gx = s->ug + 9 * s->uof[p] + 1;
    *gy = s->ug + 9 * s->uof[p] + 5;
  }
}

/* Step 2 on nodes [lo, hi):
 * m_i, (mv)_i, f_i = sum_p [S_ip m_p, S_ip m_p v_p, -V_p sigma_p . gradS_ip + S_ip m_p b]. */
static void point_to_grid(mpm_sim *s, int lo, int hi, double bx, double by)
{
  const mpm_points *P = s->pts;
  const mpm_shape_stencil *st = s->st;
  const size_t len = (size_t)(hi - lo) * sizeof(double);
  double *nm = s->nm, *nmvx = s->nmvx, *nmvy = s->nmvy, *nfx = s->nfx, *nfy = s->nfy;
  memset(nm + lo, 0, len);
  memset(nmvx + lo, 0, len);
  memset(nmvy + lo, 0, len);
  memset(nfx + lo, 0, len);
  memset(nfy + lo, 0, len);
  const unsigned width = (unsigned)(hi - lo);
  const int bbar = s->ug != NULL;
  for (size_t p = 0; p < P->n; p++) {
    const int *node = st->node + p * MPM_STENCIL_W;
    const int c = st->count[p];
    int k = 0;
    while (k < c && (unsigned)(node[k] - lo) >= width)   /* node[k] outside [lo, hi) */
      k++;
    if (k == c)
      continue;                            /* no node in the range */
    const double *S = st->S + p * MPM_STENCIL_W;
    const double *gx = st->dSx + p * MPM_STENCIL_W, *gy = st->dSy + p * MPM_STENCIL_W;
    const double m = P->mass[p], V = P->vol[p];
    const double mvx = m * P->vx[p], mvy = m * P->vy[p];
    const double sxx = P->sxx[p], syy = P->syy[p], sxy = P->sxy[p];
    const double sm = bbar ? 0.5 * (sxx + syy) : 0.0;   /* in-plane mean stress */
    const double *cgx = gx, *cgy = gy;                /* no B-bar: no correction */
    if (bbar)
      bbar_gradient(s, p, &cgx, &cgy);
    for (; k < c; k++) {
      const int i = node[k];
      if ((unsigned)(i - lo) >= width)
        continue;                          /* another range's node */
      const double Sk = S[k], gxk = gx[k], gyk = gy[k], Sm = Sk * m;
      nm[i] += Sm;
      nmvx[i] += Sk * mvx;
      nmvy[i] += Sk * mvy;
      nfx[i] += -V * (sxx * gxk + sxy * gyk) + Sm * bx;  /* -V sigma.gradS + S m b */
      nfy[i] += -V * (sxy * gxk + syy * gyk) + Sm * by;
      if (bbar) {                          /* mean stress on the unit's B-bar gradient */
        nfx[i] -= V * sm * (cgx[k] - gxk);
        nfy[i] -= V * sm * (cgy[k] - gyk);
      }
    }
  }
}

/* Boundary conditions on nodes [lo, hi) only: they are a per-node mask
 * (bc.h), so a view of the mask from node lo applies them to that range. */
static void bc_apply_range(const mpm_bc *bc, int lo, int hi, double *ax, double *ay)
{
  mpm_bc part = *bc;
  part.fix += lo;
  if (part.normal)
    part.normal += 2 * lo;
  part.nnodes = hi - lo;
  mpm_bc_apply(&part, ax + lo, ay + lo);
}

/* Step 3 on nodes [lo, hi): boundary conditions, (mv)_i += dt f_i,
 * v_i = (mv)_i/m_i. A wall zeroes the constrained components of (mv)_i and
 * of f_i ([DK15] section 4: momentum fixed, its update suppressed). The
 * acceleration the points receive is the change of nodal velocity over the
 * step, a_i = f_i/m_i + (v_i^bc - v_i^n)/dt, where v_i^n = (mv)_i/m_i as
 * mapped and v_i^bc the same after the wall acted: f_i/m_i on free
 * components (the jump is exactly 0 there) and -v_i^n/dt on constrained
 * ones. With a_i = f_i/m_i = 0 there instead (boundary.wall_acceleration =
 * "zero", [DK15] read literally), a point stopped by a wall would keep its
 * velocity for ever (FLIP only adds increments): its position follows the
 * grid and stays put, but it reports kinetic energy it does not have, and a
 * kinetic-energy stop test never fires; in steady flow along a wall the jump
 * kicks the points beside it every step instead (docs/model.md).
 * With delta shape functions a node lighter than mlight (1e-3 of the mean
 * point mass: the points near it lie within about a thousandth of a unit of
 * its far edge) takes the body force only. Its internal force
 * -V sigma.gradS does not shrink with its weight S, so f_i/m_i grows as 1/S
 * when a stressed point crosses into an empty unit, and that velocity, times
 * gradS, enters L_p: a point's volume overflowed (1e111 m^2) this way at a
 * heap's surface. uGIMP gradients vanish with the weights (mlight = 0). */
static void grid_update(mpm_sim *s, int lo, int hi, double bx, double by)
{
  const double dt = s->dt, mt = s->mtiny, ml = s->mlight;
  const double idt = s->cfg.bc.wall_acceleration == MPM_WALL_ZERO ? 0.0 : 1.0 / s->dt;
  for (int i = lo; i < hi; i++) {                       /* v_i^n, before the wall */
    double m = s->nm[i];
    s->nvx[i] = m > mt ? s->nmvx[i] / m : 0.0;
    s->nvy[i] = m > mt ? s->nmvy[i] / m : 0.0;
    if (m < ml) {                                       /* light node: body force only */
      s->nfx[i] = m * bx;
      s->nfy[i] = m * by;
    }
  }
  bc_apply_range(&s->bc, lo, hi, s->nmvx, s->nmvy);
  bc_apply_range(&s->bc, lo, hi, s->nfx, s->nfy);
  for (int i = lo; i < hi; i++) {
    double m = s->nm[i];
    if (m > mt) {
      const double jx = (s->nmvx[i] / m - s->nvx[i]) * idt;  /* wall's velocity jump / dt (or 0) */
      const double jy = (s->nmvy[i] / m - s->nvy[i]) * idt;
      s->nmvx[i] += dt * s->nfx[i];
      s->nmvy[i] += dt * s->nfy[i];
      s->nax[i] = s->nfx[i] / m + jx;
      s->nay[i] = s->nfy[i] / m + jy;
      s->nvx[i] = s->nmvx[i] / m;
      s->nvy[i] = s->nmvy[i] / m;
    } else {
      s->nax[i] = s->nay[i] = s->nvx[i] = s->nvy[i] = 0.0;
    }
  }
}

/* Steps 2-3, each thread on its own range of nodes. */
static void grid_phase(mpm_sim *s, double bx, double by)
{
  count_busy_nodes(s);
#pragma omp parallel
  {
    int t = 0, nt = 1;
#ifdef _OPENMP
    t = omp_get_thread_num();
    nt = omp_get_num_threads();
#endif
    const int lo = range_start(s, t, nt), hi = range_start(s, t + 1, nt);
    point_to_grid(s, lo, hi, bx, by);
    grid_update(s, lo, hi, bx, by);
  }
}

/* Steps 4-5 for point p: v_p += dt sum S a_i (FLIP; blended with the PIC
 * velocity sum S v_i when time.flip < 1); x_p += dt sum S v_i;
 * L_p = sum v_i (x) gradS (its in-plane part; L is zero otherwise);
 * V_p *= exp(dt tr L_p). */
static void grid_to_point(mpm_sim *s, size_t p, mpm_mat3 *L, double vgrid[2])
{
  mpm_points *P = s->pts;
  const mpm_shape_stencil *st = s->st;
  const double dt = s->dt;
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
  if (s->ug) {
    /* B-bar: tr L is replaced by the unit's divergence, the volume-weighted
     * mean of its points' tr L, i.e. its rate of area change (the in-plane
     * mean stress does work on it in point_to_grid, so the pair conserves
     * energy). */
    const double *cgx, *cgy;
    double div = 0.0;
    bbar_gradient(s, p, &cgx, &cgy);
    for (int k = 0; k < st->count[p]; k++)
      div += s->nvx[node[k]] * cgx[k] + s->nvy[node[k]] * cgy[k];
    const double corr = 0.5 * (div - lxx - lyy);
    lxx += corr;
    lyy += corr;
  }
  const double fl = s->cfg.time.flip;                     /* FLIP share (1: [DK15]) */
  P->vx[p] = fl * (P->vx[p] + dt * ax) + (1.0 - fl) * vx;  /* v_p = fl v_FLIP + (1-fl) v_PIC */
  P->vy[p] = fl * (P->vy[p] + dt * ay) + (1.0 - fl) * vy;
  P->x[p] += dt * vx;
  P->y[p] += dt * vy;
  vgrid[0] = vx;
  vgrid[1] = vy;
  P->vol[p] *= exp(dt * (lxx + lyy));                     /* V *= exp(dt tr L) */
  L->m[0][0] = lxx;
  L->m[0][1] = lxy;
  L->m[1][0] = lyx;
  L->m[1][1] = lyy;
}

/* Density the update of point p sees: m / V_{n+1} (point rule), or the
 * element / hybrid value computed for the step ([D-thesis] §3.4). */
static double state_rho(const mpm_sim *s, size_t p)
{
  return s->dens ? s->rho[p] : s->pts->mass[p] / s->pts->vol[p];  /* rho_{n+1} */
}

/* Step 6 for point p: n substeps of length h of a model's update with L
 * fixed; lap is the Laplacian of g its unit sees and isp the p^-1/2 of its
 * g^2 term (0: its own; nonlocal models only). Returns 0 when the stress
 * became non-finite. */
static int constitutive(mpm_sim *s, mpm_material_update_fn update, size_t p, const mpm_mat3 *L,
                        double h, int n, double lap, double isp)
{
  mpm_points *P = s->pts;
  mpm_mpoint mp = {
    .sigma = mpm_points_stress(P, p),
    .rho = state_rho(s, p),
    .g = P->g[p], .lap = lap, .isp = isp, .gdp = P->gdp[p], .state = P->state[p],
  };
  for (int k = 0; k < n; k++)
    update(&s->par, L, h, &mp);
  P->sxx[p] = mp.sigma.xx;
  P->syy[p] = mp.sigma.yy;
  P->szz[p] = mp.sigma.zz;
  P->sxy[p] = mp.sigma.xy;
  P->g[p] = mp.g;
  P->gdp[p] = mp.gdp;
  P->state[p] = mp.state;
  return isfinite(mp.sigma.xx + mp.sigma.yy + mp.sigma.zz + mp.sigma.xy);
}

/* Step 7 for point p, moved by the grid velocity vgrid: walls hold, periodic
 * wrap, and the absorbing layer of [DK-silo] section 7.1 (upward motion high
 * in a silo is elastic waves). */
static void bookkeeping(mpm_sim *s, size_t p, const double vgrid[2])
{
  mpm_points *P = s->pts;
  /* Walls hold. A disconnected point is a free particle: nothing but the
   * wall stops it, so its velocity into the wall is limited to the grid's.
   * A dense one keeps its FLIP velocity, whose wall part the held nodes'
   * a_i already take back (step 3). */
  double vx = P->vx[p], vy = P->vy[p];
  mpm_bc_clamp(&s->bc, &s->mesh, &P->x[p], &P->y[p], &vx, &vy, vgrid[0], vgrid[1]);
  if (P->state[p] != MPM_STATE_DENSE) {
    P->vx[p] = vx;
    P->vy[p] = vy;
  }
  if (P->y[p] >= s->cfg.absorb.above && P->vy[p] > 0.0)
    P->vy[p] *= s->cfg.absorb.factor;
  if (s->mesh.periodic_x || s->mesh.periodic_y)
    mpm_mesh_wrap(&s->mesh, &P->x[p], &P->y[p]);
}

/* Steps 4-7 point by point for a local model (once the grid is known the
 * points are independent): grid-to-point, constitutive update in n_sub
 * substeps, bookkeeping. Returns the largest index of a point whose stress
 * became non-finite, or -1. */
static long point_phase(mpm_sim *s, const mpm_material_type *mat)
{
  mpm_points *P = s->pts;
  const double h = s->dt / s->n_sub;
  long bad = -1;
#pragma omp parallel for schedule(static) reduction(max : bad)
  for (size_t p = 0; p < P->n; p++) {
    mpm_mat3 L = {{{0.0}}};
    double vgrid[2];
    grid_to_point(s, p, &L, vgrid);
    if (!constitutive(s, mat->update, p, &L, h, s->n_sub, 0.0, 0.0))
      bad = (long)p > bad ? (long)p : bad;
    bookkeeping(s, p, vgrid);
  }
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

/* L_p as stored for the substeps. */
static mpm_mat3 stored_L(const mpm_sim *s, size_t p)
{
  mpm_mat3 L = {{{0.0}}};
  L.m[0][0] = s->lxx[p];
  L.m[0][1] = s->lxy[p];
  L.m[1][0] = s->lyx[p];
  L.m[1][1] = s->lyy[p];
  return L;
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
  mpm_points *P = s->pts;
  int rc = reserve_L(s, err);
  if (rc != MPM_OK)
    return rc;
#pragma omp parallel for schedule(static)
  for (size_t p = 0; p < P->n; p++) {
    mpm_mat3 L = {{{0.0}}};
    double vgrid[2];
    grid_to_point(s, p, &L, vgrid);
    s->lxx[p] = L.m[0][0];
    s->lxy[p] = L.m[0][1];
    s->lyx[p] = L.m[1][0];
    s->lyy[p] = L.m[1][1];
    bookkeeping(s, p, vgrid);
  }
  return MPM_OK;
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
  long bad = -1;
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
  size_t n = P->n;
  update_density(s, nl->unit);  /* the units just frozen */
  if (steady) {                              /* g given: the substeps with L fixed */
#pragma omp parallel for schedule(static) reduction(max : bad)
    for (size_t p = 0; p < n; p++) {
      mpm_mat3 L = stored_L(s, p);
      if (!constitutive(s, s->mat->update_steady, p, &L, h, s->n_sub, 0.0, 0.0))
        bad = (long)p > bad ? (long)p : bad;
    }
    return bad;
  }
  for (int k = 0; k < s->n_sub; k++) {
    *rc = mpm_nonlocal_field(nl, s->mat, &s->par, P, s->dens ? s->rho : NULL, h, err);
    if (*rc != MPM_OK) {                     /* g_e, lap_e, isp_e of the dense points */
      mpm_err_prefix(err, *rc, "step %ld, t = %.6g s", s->step + 1, s->t + s->dt);
      return -1;
    }
#pragma omp parallel for schedule(static) reduction(max : bad)
    for (size_t p = 0; p < n; p++) {
      mpm_mat3 L = stored_L(s, p);
      if (!constitutive(s, s->mat->update, p, &L, h, 1, mpm_nonlocal_point_lap(nl, p),
                        mpm_nonlocal_point_isp(nl, p)))
        bad = (long)p > bad ? (long)p : bad;
    }
  }
  return bad;
}

/* Steps 4-7 for a local model with the element or hybrid density: the
 * density of a unit needs every point at x_{n+1}, so all points move first
 * (L_p stored, walls and periodic wrap applied), then the unit sums run in
 * point order and the points are updated. Returns as point_phase. */
static long density_phase(mpm_sim *s, const mpm_material_type *mat, int *rc, mpm_err *err)
{
  mpm_points *P = s->pts;
  const double h = s->dt / s->n_sub;
  long bad = -1;
  if ((*rc = move_points(s, err)) != MPM_OK)
    return -1;
  update_density(s, NULL);
#pragma omp parallel for schedule(static) reduction(max : bad)
  for (size_t p = 0; p < P->n; p++) {
    mpm_mat3 L = stored_L(s, p);
    if (!constitutive(s, mat->update, p, &L, h, s->n_sub, 0.0, 0.0))
      bad = (long)p > bad ? (long)p : bad;
  }
  return bad;
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

int mpm_sim_step(mpm_sim *s, mpm_err *err)
{
  int rc = mpm_shape_stencil_compute(s->st, s->shape, &s->mesh, s->pts, s->t, err);
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
  if (s->ug && (rc = unit_gradients(s, err)) != MPM_OK)
    return rc;
  grid_phase(s, bx, by);
  const mpm_material_type *mat = seeding(s);
  long bad;
  if (mat->nonlocal) {
    bad = nonlocal_phase(s, &rc, err);
    if (rc != MPM_OK)
      return rc;
  } else if (s->dens) {
    bad = density_phase(s, mat, &rc, err);
    if (rc != MPM_OK)
      return rc;
  } else {
    bad = point_phase(s, mat);
  }
  if (bad >= 0)                              /* a non-finite stress: what, where, why */
    return mpm_sim_check_state(s, s->t + s->dt, err);
  s->t += s->dt;
  s->step++;
  if ((rc = mpm_sim_check_speeds(s, s->t, err)) != MPM_OK)
    return rc;
  return mpm_sim_remove_points(s, s->t, err);
}
