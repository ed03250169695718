/* step.c: simulation set-up and the explicit Update-Stress-Last MPM step
 * (MODEL.md section 2, [DK15] section 3.1), for either dimension: the step
 * names no dimension, it calls the kernels of the run's (s->k,
 * solver_internal.h).
 *
 * One step: weights (once) -> point-to-grid (mass, momentum, force) -> grid
 * update with boundary conditions -> grid-to-point (FLIP velocity, position,
 * velocity gradient) -> volume -> constitutive update -> walls and periodic
 * wraps. The constitutive update runs in n_sub substeps of dt/n_sub with L
 * fixed, through the model's batch update (the material table).
 * A nonlocal model (NGF, [DK-silo] section 5.2) moves the points first, freezes
 * their units, and per substep has nonlocal/ rebuild the element field (the
 * model's dense points, g_e, lap_e by the chosen diffusion solver: field.h)
 * before the point updates (nonlocal_phase); a model with a seeding phase
 * runs as its local model before t_seed, then seeds its field from it
 * (seeding); one without runs its own update with lap = 0 until then.
 * The density a point's state is decided with is m / V_{n+1} by default;
 * with material.state_density = "element", "hybrid" ([D-thesis] §3.4) or "unit"
 * all points move first and the unit sums are taken from x_{n+1} before the
 * updates (density_phase, and likewise in nonlocal_phase). V_p always keeps its
 * local update. With mesh.dilatation = "unit" or "element" (B-bar, units.c)
 * the mean stress enters point-to-grid as its unit's mean, all points move
 * before tr L_p is replaced by its unit's mean (density_phase or
 * nonlocal_phase), and after the update the dense points of a unit share its
 * mean stress.
 * Threads: the weights are parallel over points; point-to-grid and the grid
 * update over bands and ranges of nodes (kernels.inc); the rest over points
 * in chunks, except the unit sums of the per-unit rules, which run in point
 * order. No sum depends on the thread count, so neither do results. */
#include "solver/solver.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "scenario/scenario.h"
#include "solver/solver_internal.h"

/* ---- set-up -------------------------------------------------------------- */

static int nodal_alloc(mpm_sim *s)
{
  const size_t n = s->mesh.nnodes > 0 ? (size_t)s->mesh.nnodes : 1;
  if (!(s->nm = calloc(n, sizeof *s->nm)))
    return MPM_ENOMEM;
  /* records of whole 4-double vectors on 32-byte boundaries */
  const size_t bytes = n * (size_t)mpm_sim_node_lanes(s->dim) * sizeof *s->nq;
  if (!(s->nq = aligned_alloc(32, bytes)))
    return MPM_ENOMEM;
  memset(s->nq, 0, bytes);
  return MPM_OK;
}

/* Per-point L storage for the phases that move every point before any
 * update (nonlocal models, the per-unit rules); once per run. */
static int L_alloc(mpm_sim *s, mpm_err *err)
{
  if (s->L[0])
    return MPM_OK;
  size_t n = s->pts->cap > 0 ? s->pts->cap : 1;
  for (int k = 0; k < s->dim * s->dim; k++)
    if (!(s->L[k] = calloc(n, sizeof(double))))
      return mpm_err_set(err, MPM_ENOMEM, "simulation: no memory for %zu velocity gradients", n);
  s->lcap = n;
  return MPM_OK;
}

/* The kinds of the mesh's 2 dim faces, in MPM_FACE_* order. */
static void face_kinds(const mpm_config *cfg, int face[6])
{
  const int f[6] = {cfg->bc.left, cfg->bc.right, cfg->bc.bottom, cfg->bc.top,
                    cfg->bc.front, cfg->bc.back};
  memcpy(face, f, sizeof f);
}

/* Per-point L storage and the nonlocal workspace for models that need them. */
static int nonlocal_alloc(mpm_sim *s, mpm_err *err)
{
  if (!s->mat->nonlocal)
    return MPM_OK;
  const mpm_config *cfg = &s->cfg;
  int face[6];
  face_kinds(cfg, face);
  int rc = mpm_nonlocal_alloc(&s->nl, &s->mesh, face, cfg->material.g_average, s->pts->cap, err);
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

/* The outlet of the input on the bc of mesh m. */
static int set_outlet(mpm_sim *s, mpm_err *err)
{
  const mpm_config *cfg = &s->cfg;
  const double lo[2] = {cfg->outlet.from, cfg->outlet.from2};
  const double hi[2] = {cfg->outlet.to, cfg->outlet.to2};
  const int shape = cfg->outlet.shape == MPM_OUTLET_DISC ? MPM_BC_OUTLET_DISC : MPM_BC_OUTLET_BOX;
  return mpm_bc_set_outlet(&s->bc, &s->mesh, cfg->outlet.edge - MPM_OUTLET_LEFT, shape, lo, hi,
                           cfg->outlet.closed, cfg->outlet.ends == MPM_OUTLET_ENDS_FIXED, err);
}

/* mpm_sim_create's part from the input: mesh, faces, walls, shape, points,
 * nodal records and the workspaces of the options. */
static int build(mpm_sim *s, mpm_err *err)
{
  const mpm_config *cfg = &s->cfg;
  int rc = mpm_mesh_from_config(&s->mesh, cfg, err);
  if (rc == MPM_OK) {
    int face[6];
    face_kinds(cfg, face);
    rc = mpm_bc_setup(&s->bc, &s->mesh, face, err);
  }
  if (rc == MPM_OK && cfg->outlet.edge != MPM_OUTLET_NONE)
    rc = set_outlet(s, err);
  if (rc == MPM_OK && cfg->wall.nvert > 0)    /* in 3D its prism along z */
    rc = mpm_bc_add_polygon(&s->bc, &s->mesh, cfg->wall.nvert, cfg->wall.px, cfg->wall.py,
                            cfg->wall.kind, NULL, err);
  if (rc == MPM_OK && !(s->shape = mpm_shape_lookup(cfg->mesh.shape)))
    rc = mpm_err_set(err, MPM_EINPUT, "mesh.shape '%s' unknown", cfg->mesh.shape);
  if (rc == MPM_OK && (!(s->pts = mpm_points_alloc_dim(1024, s->dim)) ||
                       mpm_points_set_defgrad(s->pts, s->mat->defgrad) != MPM_OK))
    rc = mpm_err_set(err, MPM_ENOMEM, "points: out of memory");
  for (int f = 0; rc == MPM_OK && f < cfg->nfill; f++)
    rc = mpm_scenario_fill(s->pts, &s->mesh, &cfg->fill[f], &s->par, cfg->gravity.gy, err);
  if (rc == MPM_OK)
    rc = mpm_sim_bodies_setup(s, err);
  if (rc == MPM_OK && (nodal_alloc(s) != MPM_OK || !(s->st = mpm_shape_stencil_alloc(0)) ||
                       !(s->bands = mpm_mesh_bands_alloc())))
    rc = mpm_err_set(err, MPM_ENOMEM, "simulation workspace: out of memory");
  if (rc == MPM_OK)
    s->located = s->shape->at_point;
  if (rc == MPM_OK)
    rc = nonlocal_alloc(s, err);
  if (rc == MPM_OK)
    rc = density_alloc(s, err);
  const size_t nu = s->mesh.nunits;
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
  s->k = s->dim == 3 ? &mpm_sim_kernels_3 : &mpm_sim_kernels_2;
  if (rc == MPM_OK)
    rc = build(s, err);
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
  if (s->shape->at_point) {                                 /* body force only below this */
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
  for (int k = 0; k < 9; k++)
    free(s->L[k]);
  for (int d = 0; d < 3; d++) {
    free(s->loc_c[d]);
    free(s->loc_l[d]);
  }
  free(s->loc_n);
  free(s->scratch);
  free(s->nm);
  free(s->nq);
  free(s->brow);
  free(s);
}

void mpm_sim_gravity(const mpm_sim *s, double t, double g[3])
{
  double r = s->cfg.gravity.t_ramp;
  double f = (r > 0.0 && t < r) ? t / r : 1.0;             /* linear ramp 0 -> 1 over t_ramp */
  g[0] = f * s->cfg.gravity.gx;
  g[1] = f * s->cfg.gravity.gy;
  g[2] = f * s->cfg.gravity.gz;
}

/* ---- the step ------------------------------------------------------------ */

typedef mpm_sim_chunk chunk;
enum { CHUNK = MPM_SIM_CHUNK };

/* The chunk's L arrays, as the kernels take them. */
static void chunk_L(chunk *ck, double *L[9])
{
  for (int k = 0; k < 9; k++)
    L[k] = ck->L[k];
}

/* Step 6 for points [a, b): n substeps of length h of the update of model
 * mat (update_steady instead when steady) with L fixed; rho, lap, isp as in
 * mpm_material_batch. Returns b - 1 when a field it or the move wrote went
 * wrong at a point of the range (mpm_sim_updated_bad), else -1. */
static long update_range(mpm_sim *s, const mpm_material_type *mat, int steady, size_t a, size_t b,
                         double *const L[9], const double *rho, const double *lap,
                         const double *isp, double h, int n)
{
  mpm_points *P = s->pts;
  const int D = s->dim, ns = D == 3 ? 6 : 4;
  mpm_material_batch bt = {.n = b - a, .dim = D, .rho = rho, .lap = lap, .isp = isp,
                           .g = P->g + a, .gdp = P->gdp + a, .state = P->state + a};
  for (int k = 0; k < D * D; k++)
    bt.L[k] = L[k];
  for (int k = 0; k < ns; k++)
    bt.sig[k] = P->sig[k] + a;
  for (int e = 0; mat->defgrad && e < 9; e++) {
    bt.F[e] = P->F[e / 3][e % 3] + a;
    bt.Fp[e] = P->Fp[e / 3][e % 3] + a;
  }
  if (steady)
    mat->update_steady(&s->par, h, n, &bt);
  else
    mat->update(&s->par, h, n, &bt);
  return mpm_sim_updated_bad(s, a, b) ? (long)b - 1 : -1;   /* while the chunk is at hand */
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
 * bookkeeping. Returns an index >= 0 when a point's update went wrong
 * (update_range), or -1. */
static long point_phase(mpm_sim *s, const mpm_material_type *mat)
{
  const size_t n = s->pts->n, nc = (n + CHUNK - 1) / CHUNK;
  const double h = s->dt / s->n_sub;
  long bad = -1;
  unsigned scan = 0;
#pragma omp parallel for schedule(static) reduction(max : bad) reduction(| : scan)
  for (size_t c = 0; c < nc; c++) {
    chunk ck;
    double *L[9];
    chunk_L(&ck, L);
    const size_t a = c * CHUNK, b = a + CHUNK < n ? a + CHUNK : n;
    s->k->move(s, a, b, L, &ck);
    long bc = update_range(s, mat, 0, a, b, L, state_rho(s, a, b, ck.rho), NULL, NULL, h,
                           s->n_sub);
    bad = bc > bad ? bc : bad;
    s->k->bookkeeping(s, a, b, &ck);
    scan |= moved_scan(s, a, b);
  }
  s->scan = scan;
  return bad;
}

/* Element, hybrid or unit density of every point from x_{n+1}, V_{n+1};
 * unit: the points' units of x_{n+1} when already found (NULL: found here). */
static void update_density(mpm_sim *s, const int *unit)
{
  if (s->dens)
    mpm_material_density_compute(s->dens, &s->mesh, s->cfg.material.state_density, s->pts,
                                 unit, s->rho);
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
  for (int k = 0; k < s->dim * s->dim; k++) {
    double *a = realloc(s->L[k], n * sizeof(double));
    if (!a)
      return mpm_err_set(err, MPM_ENOMEM, "simulation: no memory for %zu velocity gradients", n);
    s->L[k] = a;
  }
  s->lcap = n;
  return MPM_OK;
}

/* The stored L arrays from point a on. */
static void stored_L(const mpm_sim *s, size_t a, double *L[9])
{
  for (int k = 0; k < 9; k++)
    L[k] = s->L[k] ? s->L[k] + a : NULL;
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
    double *L[9];
    const size_t a = c * CHUNK, b = a + CHUNK < n ? a + CHUNK : n;
    stored_L(s, a, L);
    s->k->move(s, a, b, L, &ck);
    s->k->bookkeeping(s, a, b, &ck);
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
    double *L[9];
    const size_t a = c * CHUNK, b = a + CHUNK < n ? a + CHUNK : n;
    stored_L(s, a, L);
    if (nonlocal)
      for (size_t p = a; p < b; p++) {
        ck.lap[p - a] = mpm_nonlocal_point_lap(s->nl, p);
        ck.isp[p - a] = mpm_nonlocal_point_isp(s->nl, p);
      }
    long bc = update_range(s, mat, steady, a, b, L, state_rho(s, a, b, ck.rho),
                           nonlocal ? ck.lap : NULL, nonlocal ? ck.isp : NULL, h, n_sub);
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
  int rc = mpm_nonlocal_locate(s->nl, &s->mesh, P, err);
  if (rc != MPM_EOUTSIDE)
    return rc;
  if (mpm_sim_check_state(s, s->t + s->dt, err) != MPM_OK)
    return MPM_ENONFINITE;
  for (size_t p = 0; p < P->n; p++) {
    const double x[3] = {P->x[p], P->y[p], s->dim == 3 ? P->z[p] : 0.0};
    int c[3];
    if (mpm_mesh_unit(&s->mesh, x, c) == MPM_OK)
      continue;
    if (s->dim == 3)
      return mpm_err_set(err, MPM_EOUTSIDE, "point %d left the mesh at (%.6g, %.6g, %.6g) m, "
                         "t = %.6g s", P->id[p], P->x[p], P->y[p], P->z[p], s->t + s->dt);
    return mpm_err_set(err, MPM_EOUTSIDE, "point %d left the mesh at (%.6g, %.6g) m, t = %.6g s",
                       P->id[p], P->x[p], P->y[p], s->t + s->dt);
  }
  return rc;
}

/* Steps 4-7 for a nonlocal model ([DK-silo] section 5.2; MODEL.md section 5):
 * grid-to-point and bookkeeping first (L_p stored), the points that left
 * through the outlet removed, membership frozen, then per substep: dense
 * flags, element g (summed band by band: no dependence on the thread
 * count), its Laplacian (0 while a model without a seeding model runs
 * locally), and the point updates with lap_e.
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
  const int local = s->t < s->par.t_seed - 1e-9 * s->dt;   /* no seeding model: lap = 0 */
  long bad = -1;
  for (int k = 0; k < s->n_sub; k++) {
    *rc = mpm_nonlocal_field(nl, s->mat, &s->par, P, s->dens ? s->rho : NULL, h, local, err);
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
 * model with a seeding model runs as that local model while t < t_seed,
 * then sets the field of each dense point from that run (g = gdot_p / mu).
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

/* The outlet opens at t_open: its nodes are freed, and for a nonlocal
 * model its unit faces become a free surface of g (a disc's, unit by unit). */
static int open_outlet(mpm_sim *s, mpm_err *err)
{
  mpm_bc_open_outlet(&s->bc);
  if (!s->nl)
    return MPM_OK;
  int lo[3], hi[3];
  const int f = mpm_bc_outlet_faces(&s->bc, &s->mesh, lo, hi);
  if (f < 0)
    return MPM_OK;
  unsigned char *open = NULL;
  if (s->bc.out_shape == MPM_BC_OUTLET_DISC) {
    if (!(open = calloc(s->mesh.nunits, 1)))
      return mpm_err_set(err, MPM_ENOMEM, "simulation: no memory for the outlet's unit faces");
    int c[3];
    for (c[2] = lo[2]; c[2] < hi[2]; c[2]++)
      for (c[1] = lo[1]; c[1] < hi[1]; c[1]++)
        for (c[0] = lo[0]; c[0] < hi[0]; c[0]++)
          open[mpm_mesh_unit_index(&s->mesh, c)] =
              (unsigned char)mpm_bc_outlet_face_open(&s->bc, &s->mesh, c);
  }
  const int rc = mpm_nonlocal_open_faces(s->nl, f, lo, hi, open, err);
  free(open);
  return rc;
}

/* The end of a step, once every point was updated (bad >= 0: a field of
 * some point went wrong in its update, update_range): the report of a
 * blow-up, the B-bar projection, the clock, the speed check and the
 * removal of the points that left. */
static int step_end(mpm_sim *s, long bad, mpm_err *err)
{
  if (bad >= 0) {                            /* a wrong field: what, where, why */
    const int rc = mpm_sim_check_state(s, s->t + s->dt, err);
    return rc != MPM_OK ? rc : mpm_err_set(err, MPM_ENONFINITE, "step %ld, t = %.6g s: a point "
                                           "field went wrong and was not found again",
                                           s->step + 1, s->t + s->dt);
  }
  if (s->usum)                               /* one mean stress per unit */
    mpm_sim_in_unit_project(s);
  if (s->nbody) {                            /* points back out of the bodies, which move */
    double g[3];
    mpm_sim_gravity(s, s->t, g);
    mpm_sim_bodies_points(s);
    const int rc = mpm_sim_bodies_advance(s, g, err);
    if (rc != MPM_OK)
      return rc;
  }
  s->t += s->dt;
  s->step++;
  const int rc = mpm_sim_check_speeds(s, s->t, err);
  return rc != MPM_OK ? rc : mpm_sim_remove_points(s, s->t, err);
}

/* One step (see mpm_sim_step). */
static int step(mpm_sim *s, mpm_err *err)
{
  int rc;
  if (s->cfg.outlet.edge != MPM_OUTLET_NONE && !s->bc.open &&
      s->t >= s->cfg.outlet.t_open - 1e-9 * s->dt && (rc = open_outlet(s, err)) != MPM_OK)
    return rc;                                               /* the orifice opens */
  if ((rc = s->k->weights(s, err)) != MPM_OK)
    return rc;
  double b[3];
  mpm_sim_gravity(s, s->t, b);
  if (s->usum && (rc = mpm_sim_in_unit_stress(s, err)) != MPM_OK)
    return rc;
  s->k->grid(s, b);
  if (s->nbody)
    mpm_sim_bodies_contact(s);
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
  return step_end(s, bad, err);
}

int mpm_sim_step(mpm_sim *s, mpm_err *err)
{
  const int rc = step(s, err);
  s->scan = MPM_SIM_SCAN_ALL;                /* outside a step nothing is known */
  return rc;
}
