/* state.c: a simulation's state beyond its input, taken out for a
 * checkpoint and put back into a simulation built from the same input
 * (core/state.h). */
#include "solver/solver.h"

void mpm_sim_state_get(const mpm_sim *s, mpm_run_state *st)
{
  st->pts = s->pts;
  st->t = s->t;
  st->dt = s->dt;
  st->step = s->step;
  st->n_sub = s->n_sub;
  st->mass0 = s->mass0;
  st->mass_removed = s->mass_removed;
  st->nremoved = s->nremoved;
  st->seeded = s->seeded;
  st->outlet_open = s->bc.open;
  st->frames = s->frames;
  st->frame_next = s->frame_next;
  st->check_next = s->check_next;
  st->nbody = s->nbody;
  mpm_sim_bodies_state(s, st->body);
}

int mpm_sim_state_set(mpm_sim *s, const mpm_run_state *st, mpm_err *err)
{
  /* A simulation built from the checkpoint's own input has the same step,
   * substeps and initial mass, bit for bit, and room for every point (points
   * only ever leave a run). */
  if (st->dt != s->dt || st->n_sub != s->n_sub)
    return mpm_err_set(err, MPM_EINPUT, "checkpoint: time step %.17g s with %d substeps, the "
                       "input gives %.17g s with %d", st->dt, st->n_sub, s->dt, s->n_sub);
  if (st->mass0 != s->mass0)
    return mpm_err_set(err, MPM_EINPUT, "checkpoint: initial mass %.17g kg/m, the input gives "
                       "%.17g kg/m", st->mass0, s->mass0);
  if (!st->pts || st->pts->n > s->pts->cap)
    return mpm_err_set(err, MPM_EINPUT, "checkpoint: %zu points, more than the %zu of the input",
                       st->pts ? st->pts->n : 0, s->pts->n);
  if (st->pts->dim != s->pts->dim)
    return mpm_err_set(err, MPM_EINPUT, "checkpoint: points of a %dD store, the run is %dD",
                       st->pts->dim, s->pts->dim);
  if (s->pts->defgrad && !st->pts->defgrad)
    return mpm_err_set(err, MPM_EINPUT, "checkpoint: no deformation gradients, which model '%s' "
                       "needs", s->mat->name);
  if (st->nbody != s->nbody)
    return mpm_err_set(err, MPM_EINPUT, "checkpoint: %d bodies, the input gives %d", st->nbody,
                       s->nbody);
  const int defgrad = s->pts->defgrad;
  int rc = mpm_points_copy(s->pts, st->pts);
  if (rc == MPM_OK)
    rc = mpm_points_set_defgrad(s->pts, defgrad);   /* a model without them drops them */
  if (rc != MPM_OK)
    return mpm_err_set(err, rc, "checkpoint: no memory for %zu points", st->pts->n);
  s->t = st->t;
  s->step = st->step;
  s->mass_removed = st->mass_removed;
  s->nremoved = st->nremoved;
  s->seeded = st->seeded;
  s->frames = st->frames;
  s->frame_next = st->frame_next;
  s->check_next = st->check_next;
  mpm_sim_bodies_set(s, st->body);
  s->stop = MPM_STOP_NONE;
  return mpm_sim_check_restored(s, err);
}
