/* run.c: the run driver: step from t = 0 to t_end, emitting frames at t = 0,
 * every frame_dt and at the end, and reporting progress. */
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

int mpm_sim_run(mpm_sim *s, mpm_frame_fn frame, mpm_progress_fn progress, void *ctx,
                mpm_err *err)
{
  double t_end = s->cfg.time.t_end, frame_dt = s->cfg.time.frame_dt;
  double eps = 1e-9 * s->dt;                 /* tolerance on time comparisons */
  long nframe = 1;                           /* next frame is at nframe * frame_dt */
  int rc = frame ? frame(ctx, s, err) : MPM_OK;
  double w0 = wall_seconds(), wlast = w0;
  long step0 = s->step;
  while (rc == MPM_OK && s->t < t_end - eps) {
    rc = mpm_sim_step(s, err);
    if (rc != MPM_OK)
      break;
    int last = s->t >= t_end - eps;
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
