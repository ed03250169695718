/* plan.c: a run's time step and substeps from its resolved input (the
 * stable step of the densest, fastest fill), and its size, before anything
 * is built: points (counted exactly, scenario/), nodes, steps, substeps, frames,
 * and estimates of the memory the run holds at its peak, of the bytes it
 * writes and of its run time. The byte counts follow the allocations of step.c, the shape,
 * nonlocal and density workspaces and io/output.c; the constants not
 * derived from them (the libraries' own memory, HDF5's metadata cache and
 * per-frame objects, the XDMF text of a frame) were measured, and the
 * Cholesky factor of the implicit diffusion is taken as N log N. Compared
 * with the peak resident memory and the bytes written of runs from 4 to
 * 409600 points, the estimates were 1.0 - 1.5 times the measured values
 * (docs/input-reference.md, "The size of a run"). */
#include "solver/solver.h"

#include <math.h>
#include <string.h>

#include "scenario/scenario.h"

/* dt = cfl min(dx, dy (, dz)) / (c_p + |v|max) at the densest, fastest fill. */
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

/* Bytes per point of a point store of dimension dim, with the deformation
 * gradients or not: every stored field it has. */
static double point_store_bytes(int dim, int defgrad)
{
  double b = 0.0;
#define ONE_(f, nm, d, u, kind)                                                          \
  b += (kind) == MPM_POINT_EVERY || ((kind) == MPM_POINT_3D && dim == 3) ||             \
               ((kind) == MPM_POINT_DEFGRAD && defgrad)                                 \
           ? (double)sizeof(((mpm_points *)0)->f[0]) : 0.0;
  MPM_POINT_REAL_FIELDS(ONE_)
  MPM_POINT_INT_FIELDS(ONE_)
#undef ONE_
  return b;
}

/* Bytes per point of a frame in run.h5: every output field of the
 * dimension (the derived ones in double precision) and the XDMF
 * connectivity when the point count changes. */
static double frame_point_bytes(int dim)
{
  double b = 4.0;
#define OUT_(f, nm, d, u, kind) b += (kind) == MPM_POINT_EVERY || dim == 3 ? 8.0 : 0.0;
#define OUT_INT_(f, nm, d, u, kind) b += (kind) == MPM_POINT_EVERY || dim == 3 ? 4.0 : 0.0;
  MPM_POINT_FIELDS(OUT_, OUT_INT_, OUT_)
#undef OUT_
#undef OUT_INT_
  return b;
}

/* Bytes per point of the weights of a step: the located points' units
 * and local coordinates, the plane's stencil at its widest, the factorised
 * weights of a separable shape on boxes, or the stencil list of 3D. */
static double weights_bytes(const mpm_config *cfg)
{
  const mpm_shape_type *t = mpm_shape_lookup(cfg->mesh.shape);
  const int dim = cfg->mesh.nz > 0 ? 3 : 2;
  const double list = sizeof(int) + (double)(dim == 3 ? 64 : 16) *
                      (sizeof(int) + (1 + dim) * sizeof(double));
  if (dim == 2 || !t)
    return list;
  if (t->at_point)
    return dim * (sizeof(int) + sizeof(double)) + sizeof(int);
  return t->separable && !t->convect ? sizeof(mpm_shape_axes) + 2 * sizeof(int) : list;
}

/* Measured (HDF5 1.10.8, Debian 12): a run of 4 points holds 15 MB, and
 * HDF5's metadata cache adds about 240 kB per frame written (with the
 * frames' datasets in checksummed chunks: 160 kB contiguous) up to 56 MB;
 * a frame's HDF5 objects take 10.4 kB of run.h5 besides its data, its XDMF
 * grid 4.4 kB and its diagnostics row 0.14 kB. The example over 26, 101
 * and 501 frames peaks at 23.2, 41.8 and 68.6 MB against estimates of
 * 25.0, 43.0 and 76.8 MB. */
#define BASE_BYTES (16.0 * (1 << 20))
#define H5_CACHE_PER_FRAME (240.0 * 1024)
#define H5_CACHE_MAX (56.0 * (1 << 20))
enum {
  FRAME_META_BYTES = 11 << 10, /* HDF5 objects of one frame (19 datasets with attributes,
                                  the XY view) */
  FRAME_TEXT_BYTES = 5 << 10,  /* a frame's XDMF grid and diagnostics row */
  HEADER_BYTES = 64 << 10      /* run.h5 header, mesh lines excepted */
};

/* Bytes of the workspaces per point, per node and per unit for cfg. */
static double workspace_bytes(const mpm_config *cfg, double points, double nodes, double units)
{
  const mpm_material_type *mt = mpm_material_lookup(cfg->material.model);
  const int nonlocal = mt && mt->nonlocal;
  const int density = cfg->material.state_density != MPM_DENSITY_POINT;
  const int extent = cfg->material.g_average == MPM_NONLOCAL_EXTENT;
  const int dim = cfg->mesh.nz > 0 ? 3 : 2, parts = 1 << dim;
  double per_point = point_store_bytes(dim, mt && mt->defgrad)  /* the store */
                     + weights_bytes(cfg)
                     + sizeof(double) + 1.0;                   /* output work, removal flags */
  const int bbar = cfg->mesh.dilatation != MPM_DILATATION_POINT;
  if (nonlocal || density || bbar)
    per_point += dim * dim * sizeof(double);                   /* L_p kept over the substeps */
  if (density)
    per_point += sizeof(double);
  if (nonlocal)
    per_point += sizeof(int) + 1 + sizeof(double)              /* unit, dense, p_n */
                 + (extent ? parts * (sizeof(int) + sizeof(double)) : 0);
  if (bbar)
    per_point += sizeof(int);                                  /* the unit of each point */
  double per_node = (1 + mpm_sim_node_lanes(dim) + 4) * sizeof(double)  /* m_i, the record, */
                    + sizeof(int) + 2 + 2 * sizeof(double);  /* ... and the bc */
  if (cfg->time.transfer == MPM_TRANSFER_APIC)
    per_node += dim * sizeof(double);                          /* the nodes' positions */
  double per_unit = 0.0;
  if (nonlocal)
    per_unit += 6 * sizeof(double);
  if (density)
    per_unit += 4 * sizeof(double);
  if (bbar)
    per_unit += (cfg->mesh.dilatation == MPM_DILATATION_ELEMENT ? 3 + 2 * dim : 2) * sizeof(double);
  if (nonlocal && cfg->material.diffusion == MPM_DIFFUSION_IMPLICIT)  /* the matrix, its */
    per_unit += 200.0 + 16.0 * log2(units + 2.0);  /* Cholesky factor (nested-dissection
                                                       fill: ~ N log N) and the vectors */
  return points * per_point + nodes * per_node + units * per_unit;
}

/* The run time on one thread: points x steps x (a particle-step + (n_sub -
 * 1) particle-substeps), at rates of scripts/bench on the 2-core Xeon this
 * is developed on (README, "Performance"): a plane particle-step at 4.7e6
 * a second (the silo's 2.02e7 with the [DK15] scheme, scaled by the
 * instructions of the default scheme, 1731 against 400 a particle-step;
 * the slower of the plane figures), a 3D one at 4.0e6 (silo3d with
 * ngf_hyper, the slower of the 3D figures; with mu(I) 1.0e7), a further substep at 7.9e6 (scripts/bench-diffusion: the NGF silo
 * with the explicit diffusion at 405 substeps a step, field and update; a
 * local model's substep, the update alone, is cheaper). Good to a factor of
 * a few: enough to tell an hour from a month. */
#define STEP_SECONDS_2D (1.0 / 4.7e6)
#define STEP_SECONDS_3D (1.0 / 4.0e6)
#define SUBSTEP_SECONDS (1.0 / 7.9e6)

void mpm_sim_estimate(const mpm_config *cfg, mpm_sim_size *sz)
{
  memset(sz, 0, sizeof *sz);
  mpm_mesh m;
  if (mpm_mesh_from_config(&m, cfg, NULL) != MPM_OK)
    return;
  size_t points = 0;
  for (int f = 0; f < cfg->nfill; f++) {
    sz->fill_points[f] = mpm_scenario_count(&cfg->fill[f], &m);
    points += sz->fill_points[f];
  }
  mpm_sim_estimate_points(cfg, points, sz);
}

void mpm_sim_estimate_points(const mpm_config *cfg, size_t points, mpm_sim_size *sz)
{
  mpm_mesh m;
  if (mpm_mesh_from_config(&m, cfg, NULL) != MPM_OK)
    return;
  const int dim3 = m.dim == 3;
  sz->points = points;
  sz->nodes = (long)(cfg->mesh.nx + 1) * (cfg->mesh.ny + 1) * (dim3 ? cfg->mesh.nz + 1 : 1);
  sz->dt_stable = mpm_sim_stable_dt(cfg);
  int n_sub;
  mpm_sim_time_plan(cfg, &sz->dt, &n_sub);
  sz->n_sub = mpm_sim_substeps(cfg, sz->dt);
  sz->steps = ceil(cfg->time.t_end / sz->dt * (1.0 - 1e-12));
  /* one frame at t = 0, at most one per step on the schedule, one at the end */
  sz->frames = 2.0 + fmin(sz->steps, floor(cfg->time.t_end / cfg->time.frame_dt));
  const double n = (double)sz->points, units = (double)m.nunits;
  sz->sub_seconds = n * sz->steps * (sz->n_sub - 1.0) * SUBSTEP_SECONDS;
  sz->seconds = n * sz->steps * (dim3 ? STEP_SECONDS_3D : STEP_SECONDS_2D) + sz->sub_seconds;
  const mpm_material_type *mt = mpm_material_lookup(cfg->material.model);
  const double store = point_store_bytes(m.dim, mt && mt->defgrad);
  sz->memory = BASE_BYTES + fmin(sz->frames * H5_CACHE_PER_FRAME, H5_CACHE_MAX) +
               workspace_bytes(cfg, n, (double)sz->nodes, units) +
               n * store;                            /* a checkpoint assembled in memory */
  const double frame = n * frame_point_bytes(m.dim) + FRAME_META_BYTES + FRAME_TEXT_BYTES;
  const double checkpoint = 2.0 * (n * store + HEADER_BYTES);  /* + its temporary */
  sz->output = HEADER_BYTES + 8.0 * (cfg->mesh.nx + cfg->mesh.ny + (dim3 ? cfg->mesh.nz : 0)) +
               sz->frames * frame + checkpoint;
}
