/* state.h: the state of a run beyond its resolved input, as plain data:
 * what a checkpoint holds so that the run continues exactly (bitwise) as if
 * it had not stopped. solver/ takes it from a simulation and puts it back
 * (mpm_sim_state_get, mpm_sim_state_set); io/ writes and reads it with the
 * resolved input (mpm_io_checkpoint_write, _read). Everything else a step
 * uses is rebuilt from the input: the mesh, boundary masks, workspaces, the
 * stencil and nodal values of each step, the fluidity and density unit sums
 * and the implicit diffusion's factor (a function of the filled units and
 * the step, refactored on the first step after a restart to the same
 * values). */
#ifndef MPM_CORE_STATE_H
#define MPM_CORE_STATE_H

#include <stddef.h>

#include "core/config.h"
#include "core/points.h"

/* A rigid body's state (bc/body.h): where it is, how it moves, what the
 * material did to it over the last step. */
typedef struct mpm_body_state {
  double c[3];           /* centre [m] */
  double theta;          /* turn about its axis [rad] */
  double v[4];           /* velocity x, y, z [m/s] and about the axis [rad/s] */
  double f[3], tq[3];    /* force [N; plane N/m] and torque about the centre [N m; plane
                            N m/m] of the material on the body over the last step */
  long npushed;          /* points put back on its surface so far */
} mpm_body_state;

typedef struct mpm_run_state {
  mpm_points *pts;       /* every stored field of every point, in order, and next_id */
  double t, dt;          /* time and time step [s] */
  long step;             /* steps taken */
  int n_sub;             /* constitutive substeps per step */
  double mass0;          /* initial mass [kg/m] (tells that the input is the run's) */
  double mass_removed;   /* mass of the points removed so far [kg/m] */
  long nremoved;         /* their number */
  int seeded;            /* NGF: the fluidity was seeded from the local run */
  int outlet_open;       /* the outlet has opened */
  long frames;           /* frames written (the run driver's schedule) */
  long frame_next;       /* the next frame at frame_next * frame_dt */
  long check_next;       /* the next checkpoint at check_next * checkpoint_dt */
  int nbody;             /* the input's bodies, in its order */
  mpm_body_state body[MPM_MAX_BODIES];
  /* Kept by the program rather than the solver: the time and region mass of
   * every frame so far, for the flow-rate fit at the end of a run. */
  size_t nseries;
  double *series_t, *series_m;
} mpm_run_state;

#endif
