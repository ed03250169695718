/* solver.h: the explicit Update-Stress-Last MPM step and the run driver
 * (MODEL.md section 2).
 *
 * mpm_sim owns everything one run needs; it is built once from a resolved
 * mpm_config ("plan"), then stepped ("execute"). Workspace (nodal arrays,
 * per-point arrays) is allocated at creation or at the first step that needs
 * it, and grows only when points are added. */
#ifndef MPM_SOLVER_SOLVER_H
#define MPM_SOLVER_SOLVER_H

#include <stddef.h>

#include "bc/bc.h"
#include "bc/body.h"
#include "core/config.h"
#include "core/error.h"
#include "core/points.h"
#include "core/state.h"
#include "diag/diag.h"
#include "material/density.h"
#include "material/material.h"
#include "mesh/mesh.h"
#include "nonlocal/field.h"
#include "nonlocal/nonlocal.h"
#include "shape/shape.h"

struct mpm_sim_kernels;

typedef struct mpm_sim {
  mpm_config cfg;                 /* resolved input (copy) */
  int dim;                        /* 2 (plane strain) or 3: the mesh's */
  mpm_mesh mesh;
  mpm_bc bc;
  const mpm_shape_type *shape;
  const mpm_material_type *mat;
  mpm_material_params par;
  mpm_points *pts;
  const struct mpm_sim_kernels *k;  /* the step's kernels for the run's dimension (kernels.c) */

  /* weights of the step: a shape whose weights are the element basis at the
   * point (located = 1) keeps each point's unit and local coordinates; the
   * others store a stencil */
  int located;
  int *loc_c[3];                  /* [loc_cap] the unit of each point along each axis */
  int *loc_n;                     /* [loc_cap] storage id of the unit's first corner */
  double *loc_l[3];               /* [loc_cap] the local coordinates in it */
  size_t loc_cap;
  mpm_shape_stencil *st;          /* the stored stencil (computed when a step needs it) */
  mpm_mesh_bands *bands;          /* the points by bands of unit rows, for point-to-grid */
  void *scratch;                  /* [scap doubles] for reordering the point store */
  size_t scap;

  /* nodal workspace [mesh.nnodes] */
  double *nm;                     /* m_i */
  double *nq;                     /* records (mpm_sim_node): after point-to-grid
                                   * ((mv)_1..D, f_1..D), after the grid update
                                   * (v_1..D, a_1..D); in 3D then m_i and a pad */

  /* constitutive substepping and the nonlocal fluidity (MODEL.md section 5) */
  int n_sub;                      /* constitutive substeps per step, L fixed */
  mpm_nonlocal *nl;               /* element g and Laplacian; NULL for local models */
  double *L[9];                   /* [lcap] L_p of the step, kept over the substeps:
                                     L[D i + j] = dv_i/dx_j */
  size_t lcap;                    /* length of the L arrays */
  int seeded;                     /* NGF: 1 once g was seeded from the local run */

  /* density of the state decision ([D-thesis] §3.4; cfg.material.state_density) */
  mpm_material_density *dens;     /* unit sums; NULL for the point rule */
  double *rho;                    /* [rcap] density each point's update sees [kg/m^3] */
  size_t rcap;                    /* length of rho */
  /* mesh.dilatation = "unit" or "element" (B-bar with the mean stress per
   * unit, units.c); else NULL */
  int *uof;                       /* [ucap] the unit of each point, -1 outside the mesh */
  size_t ucap;
  int uof_moved;                  /* 1: uof holds the units of x_{n+1} of this step */
  double *xnode;                  /* APIC: [dim nnodes] the nodes' coordinates, axis by
                                     axis; else NULL */
  double *usum;                   /* [2 units] per unit: sum V_p, sum V_p f_p */
  double *uel;                    /* "element": [(1 + 2 dim) units] per unit: fill of a
                                     filled unit (else 0), centroid and slope of s_m */

  double t, dt;                   /* current time, time step [s] */
  long step;
  double mass0;                   /* initial mass, for bookkeeping */
  int stop;                       /* enum mpm_stop_reason (diag/diag.h): why the run
                                   * ended, MPM_STOP_NONE while it runs */
  double stop_value;              /* the measured value that fired the stop test */
  double mtiny;                   /* nodes lighter than this are skipped */
  double mlight;                  /* nodes lighter than this take the body force only */
  double stiny;                   /* mtiny / the lightest point: a node of weight above
                                     this in a point's stencil is not empty */
  double mass_removed;            /* mass of the points removed so far [kg/m] */
  unsigned scan;                  /* what the point loops of the step saw once the points
                                     had moved (MPM_SIM_SCAN_*): a clear bit lets the
                                     step skip a scan over all points; MPM_SIM_SCAN_ALL
                                     outside a step */
  long nremoved;                  /* their number */

  /* The run driver's schedule (run.c), here so that a checkpoint holds it. */
  long frames;                    /* frames emitted so far */
  long frame_next;                /* the next frame is due at frame_next * frame_dt */
  long check_next;                /* the next checkpoint at check_next * checkpoint_dt */

  /* rigid bodies (bodies.c), the input's in its order */
  int nbody;
  mpm_body body[MPM_MAX_BODIES];
  double *brow;                   /* [6 rows of nodes] per row: force and torque sums */
} mpm_sim;

/* Lanes of a nodal record in dimension dim: the 2 dim of mpm_sim.nq's
 * comment, and in 3D the mass (filled by point-to-grid) and a pad: one or
 * two whole 4-double vectors. */
static inline int mpm_sim_node_lanes(int dim)
{
  return dim == 3 ? 8 : 4;
}

/* The nodal record of node i (on a 32-byte boundary). */
static inline double *mpm_sim_node(const mpm_sim *s, int i)
{
  return s->nq + (size_t)mpm_sim_node_lanes(s->dim) * (size_t)i;
}

/* The point store is reordered by unit row (along the mesh's last axis) at
 * every step that is a multiple of this (kernels.inc), so that the points of
 * a band of rows lie together in memory. */
#define MPM_SIM_REORDER_EVERY 16

/* Build a simulation from a resolved configuration. */
int mpm_sim_create(mpm_sim **out, const mpm_config *cfg, mpm_err *err);
void mpm_sim_free(mpm_sim *s);  /* accepts NULL */

/* The time step and the number of constitutive substeps cfg resolves to
 * (time.dt, or cfl min(dx, dy) / (c_p + |v|max) at the densest, fastest fill;
 * material.n_sub, or ceil(dt / material.dt_sub)), without building a run. */
void mpm_sim_time_plan(const mpm_config *cfg, double *dt, int *n_sub);

/* The largest stable time step of cfg: time.cfl = 1 in the rule above. */
double mpm_sim_stable_dt(const mpm_config *cfg);

/* Constitutive substeps per step of length dt: material.n_sub, or
 * ceil(dt / material.dt_sub), not capped (mpm_sim_time_plan caps it at 1e6;
 * a run that needs more is refused before it is built). */
double mpm_sim_substeps(const mpm_config *cfg, double dt);

/* The size of a run, from its input alone (plan.c). Counts that may be
 * astronomical for a bad input are doubles. */
typedef struct mpm_sim_size {
  size_t points;                     /* material points of all fills (exact; before
                                        bodies carve them, until the run is built) */
  size_t fill_points[MPM_MAX_FILLS]; /* ... of each fill */
  long nodes;                        /* mesh nodes */
  double dt;                         /* the time step [s] */
  double dt_stable;                  /* the largest stable one, mpm_sim_stable_dt [s] */
  double steps;                      /* ceil(t_end / dt) */
  double n_sub;                      /* constitutive substeps per step (not capped) */
  double frames;                     /* frames written, at most */
  double memory;                     /* memory the run holds at its peak [bytes], estimate */
  double output;                     /* bytes written: run.h5, run.xdmf, diagnostics.csv,
                                        checkpoint.h5 (with its temporary copy), estimate */
  double seconds;                    /* run time on one thread, estimate (plan.c) */
  double sub_seconds;                /* ... of it, the substeps beyond the first */
} mpm_sim_size;

void mpm_sim_estimate(const mpm_config *cfg, mpm_sim_size *sz);

/* The same for a run of `points` points (the count of a built run, whose
 * bodies may have carved its fills); fill_points are left as they are. */
void mpm_sim_estimate_points(const mpm_config *cfg, size_t points, mpm_sim_size *sz);

/* The rigid bodies of the input (bodies.c): set up after the fill (a body
 * may not overlap a point of it unless it carves them out, and must hold a
 * node: MPM_EINPUT "key 'body.NAME.KEY': ..." naming the body, the key to
 * change and the count); after the grid update each corrects its nodes
 * and sums its force and torque (thread-count free); after the points have
 * moved they are put back on its surface; at the end of the step it moves
 * (a body whose centre leaves the mesh is MPM_EOUTSIDE naming it and the
 * time). */
int mpm_sim_bodies_setup(mpm_sim *s, mpm_err *err);
void mpm_sim_bodies_contact(mpm_sim *s);
void mpm_sim_bodies_points(mpm_sim *s);
int mpm_sim_bodies_advance(mpm_sim *s, const double g[3], mpm_err *err);  /* g: the step's */
/* The bodies' state for output and checkpoints, and back (s->nbody of them). */
void mpm_sim_bodies_state(const mpm_sim *s, mpm_body_state *st);
void mpm_sim_bodies_set(mpm_sim *s, const mpm_body_state *st);

/* Gravity vector at time t (linear ramp over t_ramp). */
void mpm_sim_gravity(const mpm_sim *s, double t, double g[3]);

/* One explicit USL step of length s->dt. */
int mpm_sim_step(mpm_sim *s, mpm_err *err);

/* Frame callback of the run driver, called at t = 0, every frame_dt and at the end. */
typedef int (*mpm_frame_fn)(void *ctx, const mpm_sim *s, mpm_err *err);

/* Progress callback (may be NULL): called every few steps with the wall-clock
 * rate, for the progress line. */
typedef void (*mpm_progress_fn)(void *ctx, const mpm_sim *s, double steps_per_s);

/* Remove the points below cfg.remove.below, and those outside the mesh that
 * left through the open outlet (or a free edge when cfg.remove.free_edges),
 * adding their mass to s->mass_removed. A point outside the mesh that left
 * any other way is an error (MPM_EOUTSIDE) naming it, its position and the
 * time t it got there. Called by mpm_sim_step once the points have moved
 * (for a nonlocal model before their units are frozen). */
int mpm_sim_remove_points(mpm_sim *s, double t, mpm_err *err);

/* The state of every point at time t, checked (health.c): the first
 * non-finite or absurd field (beyond 1e300 in magnitude, a volume not
 * positive, |g| above mpm_sim_g_max), extents and stresses first, else the
 * fastest point moving more than a mesh unit per step, is MPM_ENONFINITE
 * naming the point id, the field, its value, the time and the likely cause
 * (the time step against the stable one, the NGF diffusion limit, or a
 * material parameter). MPM_OK when nothing is wrong. */
int mpm_sim_check_state(const mpm_sim *s, double t, mpm_err *err);

/* The same checks of a state just restored from a checkpoint
 * (mpm_sim_state_set), at its time, the cause given as the checkpoint. */
int mpm_sim_check_restored(const mpm_sim *s, mpm_err *err);

/* The bound of |g| dt beyond which a fluidity is absurd (health.c), and
 * the bound of |g| it makes at the run's step. */
#define MPM_SIM_G_DT_MAX 1e3
double mpm_sim_g_max(const mpm_sim *s);

/* 1 if a field the step's update or move wrote is wrong at a point of
 * [a, b) (a chunk just updated): the stresses, volume, plastic shear rate,
 * and as the run has them g, F, Fp, convected extents, the affine matrix;
 * then mpm_sim_check_state finds it. One pass that vectorises. */
int mpm_sim_updated_bad(const mpm_sim *s, size_t a, size_t b);

/* The cheap test run after every step: every velocity finite and below one
 * mesh unit per step; otherwise mpm_sim_check_state's report. */
int mpm_sim_check_speeds(const mpm_sim *s, double t, mpm_err *err);

/* The bits of mpm_sim.scan: some point may leave (mpm_sim_may_leave), some
 * point is too fast (mpm_sim_too_fast). */
enum { MPM_SIM_SCAN_LEAVE = 1u, MPM_SIM_SCAN_FAST = 2u, MPM_SIM_SCAN_ALL = 3u };

/* 1 if a point of [a, b) may leave: below remove.below, outside the mesh
 * along a non-periodic direction, or at a non-finite position (one pass
 * that vectorises; a NaN fails every comparison). */
int mpm_sim_may_leave(const mpm_sim *s, size_t a, size_t b);

/* 1 if a point of [a, b) moves more than a mesh unit per step, or at a
 * non-finite velocity. */
int mpm_sim_too_fast(const mpm_sim *s, size_t a, size_t b);

/* Mass in the region of cfg.region [kg/m]. */
double mpm_sim_region_mass(const mpm_sim *s);

/* What the run driver calls besides the step; every member may be NULL. */
typedef struct mpm_sim_hooks {
  void *ctx;                      /* passed to each */
  mpm_frame_fn frame;             /* frames: at t = 0 of a new run, every frame_dt, at the
                                   * end, and at a stop on request when the step wrote none */
  mpm_progress_fn progress;
  mpm_frame_fn checkpoint;        /* every output.checkpoint_dt of simulated time, every
                                   * output.checkpoint_wall seconds, and at a stop on
                                   * request, after the step's frame (never at the end) */
  int (*stop_requested)(void *ctx);  /* asked after every step: nonzero stops the run
                                      * (MPM_STOP_REQUEST) with a checkpoint */
} mpm_sim_hooks;

/* Step until cfg.time.t_end, until a stop condition of cfg.stop holds or
 * until a stop is requested, emitting frames and checkpoints; s->stop says
 * which ended the run (set before the last frame is emitted, so the frame
 * hook can record it). A simulation restored from a checkpoint continues
 * with the schedule it had (s->frames > 0: no new frame at its start).
 * hooks may be NULL. */
int mpm_sim_run(mpm_sim *s, const mpm_sim_hooks *hooks, mpm_err *err);

/* The state beyond the input (core/state.h), for a checkpoint: st->pts
 * points into s; the frame series of st are left alone. */
void mpm_sim_state_get(const mpm_sim *s, mpm_run_state *st);

/* Put a checkpoint's state back into a simulation just built from the same
 * input. MPM_EINPUT when they do not match (time step, substeps, initial
 * mass, more points than the input makes). */
int mpm_sim_state_set(mpm_sim *s, const mpm_run_state *st, mpm_err *err);

#endif
