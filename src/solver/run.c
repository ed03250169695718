/* run.c: the run driver: step from the current time to t_end, emitting
 * frames at t = 0, every frame_dt and at the end, writing checkpoints on
 * their schedules, and reporting progress. The run ends early when the
 * kinetic energy per unit mass falls below stop.ke at t >= stop.t_min
 * (tested after every step), when the mass in cfg.region falls below
 * stop.mass, or when the program asks it to stop (a signal): then after the
 * step under way, with a checkpoint and a last frame. The schedule (frames
 * written, next frame and checkpoint) lives in mpm_sim, so a run restored
 * from a checkpoint carries on with it: no second frame at its start, the
 * same frames after. */
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

/* One frame through the hook (when there is one), counted. */
static int emit(mpm_sim *s, const mpm_sim_hooks *h, mpm_err *err)
{
  int rc = h->frame ? h->frame(h->ctx, s, err) : MPM_OK;
  s->frames++;
  return rc;
}

/* After a step: the frame it is due for, or the last one. */
static int frame_after_step(mpm_sim *s, const mpm_sim_hooks *h, double eps, mpm_err *err)
{
  const double frame_dt = s->cfg.time.frame_dt;
  if (s->stop == MPM_STOP_NONE && s->t < s->frame_next * frame_dt - eps)
    return MPM_OK;
  int rc = emit(s, h, err);
  while (s->frame_next * frame_dt <= s->t + eps)
    s->frame_next++;
  return rc;
}

/* A checkpoint, when one is due on either schedule or asked for. */
static int checkpoint_after_step(mpm_sim *s, const mpm_sim_hooks *h, int asked, double eps,
                                 double *wlast, mpm_err *err)
{
  const double cdt = s->cfg.output.checkpoint_dt, cwall = s->cfg.output.checkpoint_wall;
  const int on_time = cdt > 0.0 && s->t >= s->check_next * cdt - eps;
  const int on_wall = cwall > 0.0 && wall_seconds() - *wlast >= cwall;
  if (!h->checkpoint || s->stop != MPM_STOP_NONE || !(asked || on_time || on_wall))
    return MPM_OK;
  if (cdt > 0.0)
    while (s->check_next * cdt <= s->t + eps)
      s->check_next++;
  *wlast = wall_seconds();
  return h->checkpoint(h->ctx, s, err);
}

int mpm_sim_run(mpm_sim *s, const mpm_sim_hooks *hooks, mpm_err *err)
{
  const mpm_sim_hooks none = {0};
  const mpm_sim_hooks *h = hooks ? hooks : &none;
  const double eps = 1e-9 * s->dt;              /* tolerance on time comparisons */
  int rc = MPM_OK;
  if (s->frames == 0) {                         /* a new run: the frame at t = 0 */
    rc = emit(s, h, err);
    s->frame_next = 1;
  }
  if (s->check_next == 0)
    s->check_next = 1;
  double w0 = wall_seconds(), wlast = w0, wcheck = w0;
  long step0 = s->step;
  s->stop = MPM_STOP_NONE;
  while (rc == MPM_OK && s->stop == MPM_STOP_NONE) {
    rc = mpm_sim_step(s, err);
    if (rc != MPM_OK)
      break;
    s->stop = stop_test(s, eps);
    const int asked = s->stop == MPM_STOP_NONE && h->stop_requested &&
                      h->stop_requested(h->ctx);
    const long frames = s->frames;
    rc = frame_after_step(s, h, eps, err);
    if (rc == MPM_OK)
      rc = checkpoint_after_step(s, h, asked, eps, &wcheck, err);
    if (rc == MPM_OK && asked) {                /* stopped on request: a last frame unless */
      s->stop = MPM_STOP_REQUEST;               /* this step wrote one on schedule */
      if (s->frames == frames)
        rc = emit(s, h, err);
    }
    if (h->progress && (s->step & 63) == 0) {
      double w = wall_seconds();
      if (w - wlast > 0.5 || s->stop != MPM_STOP_NONE) {
        h->progress(h->ctx, s, (double)(s->step - step0) / (w - w0));
        wlast = w;
      }
    }
  }
  return rc;
}
