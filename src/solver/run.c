/* run.c: the run driver: step from t = 0 to t_end, emitting frames at t = 0,
 * every frame_dt and at the end, and reporting progress. The run ends early
 * when the kinetic energy per unit mass falls below stop.ke at t >= stop.t_min
 * (tested after every step), or when the mass in cfg.region falls below
 * stop.mass. */
#define _POSIX_C_SOURCE 200809L
#include "solver/solver.h"

#include <math.h>
#include <time.h>

static double wall_seconds(void)
{
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The stop reason after a step, MPM_STOP_NONE to go on. */
static int stop_test(mpm_sim *s, double eps)
{
  const mpm_config *c = &s->cfg;
  if (c->stop.ke > 0.0 && s->t >= c->stop.t_min - eps) {
    double ke = mpm_diag_kinetic_per_mass(s->pts);
    if (ke < c->stop.ke) {
      s->stop_value = ke;
      return MPM_STOP_KE;
    }
  }
  if (c->stop.mass > 0.0 && s->t >= c->stop.t_min - eps) {
    double m = mpm_sim_region_mass(s);
    if (m < c->stop.mass) {
      s->stop_value = m;
      return MPM_STOP_MASS;
    }
  }
  return s->t >= c->time.t_end - eps ? MPM_STOP_T_END : MPM_STOP_NONE;
}

int mpm_sim_run(mpm_sim *s, mpm_frame_fn frame, mpm_progress_fn progress, void *ctx,
                mpm_err *err)
{
  double frame_dt = s->cfg.time.frame_dt;
  double eps = 1e-9 * s->dt;                 /* tolerance on time comparisons */
  long nframe = 1;                           /* next frame is at nframe * frame_dt */
  int rc = frame ? frame(ctx, s, err) : MPM_OK;
  double w0 = wall_seconds(), wlast = w0;
  long step0 = s->step;
  s->stop = MPM_STOP_NONE;
  while (rc == MPM_OK && s->stop == MPM_STOP_NONE) {
    rc = mpm_sim_step(s, err);
    if (rc != MPM_OK)
      break;
    s->stop = stop_test(s, eps);
    int last = s->stop != MPM_STOP_NONE;
    if (frame && (last || s->t >= nframe * frame_dt - eps)) {
      rc = frame(ctx, s, err);
      while (nframe * frame_dt <= s->t + eps)
        nframe++;
    }
    if (progress && (s->step & 63) == 0) {
      double w = wall_seconds();
      if (w - wlast > 0.5 || last) {
        progress(ctx, s, (double)(s->step - step0) / (w - w0));
        wlast = w;
      }
    }
  }
  return rc;
}
