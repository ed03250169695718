/* jam.c: the silo classifier of [DK-silo] section 7.2 (jam.h). */
#include "diag/jam.h"

#include <math.h>

#include "core/names.h"

static const char *const class_names[] = {
  [MPM_JAM_UNSURE] = "unsure", [MPM_JAM_STATIC] = "static", [MPM_JAM_FLOWING] = "flowing",
};

const char *mpm_diag_jam_name(int cls)
{
  return mpm_names_at(class_names, MPM_NAMES_COUNT(class_names), cls);
}

double mpm_diag_dense_vy_moved(const mpm_points *prev, const mpm_points *now, double dt, int *slot,
                               size_t nslot)
{
  for (size_t q = 0; q < prev->n; q++)
    if (prev->id[q] >= 0 && (size_t)prev->id[q] < nslot)
      slot[prev->id[q]] = (int)q;
  double m = 0.0, my = 0.0;
  for (size_t p = 0; p < now->n; p++) {
    const int id = now->id[p];
    if (now->state[p] != MPM_STATE_DENSE || id < 0 || (size_t)id >= nslot)
      continue;
    const int q = slot[id];
    if (q < 0 || prev->state[q] != MPM_STATE_DENSE)
      continue;
    m += now->mass[p];
    my += now->mass[p] * (now->y[p] - prev->y[q]);
  }
  for (size_t q = 0; q < prev->n; q++)
    if (prev->id[q] >= 0 && (size_t)prev->id[q] < nslot)
      slot[prev->id[q]] = -1;
  return m > 0.0 && dt > 0.0 ? my / (m * dt) : NAN;
}

int mpm_diag_jam(size_t nf, const double *t, const double *vbar, const size_t *npoints,
                 mpm_jam *out, mpm_err *err)
{
  if (nf < 2)
    return mpm_err_set(err, MPM_EINVAL, "jam: %zu frame(s); the classifier needs two or more", nf);
  for (size_t k = 1; k < nf; k++) {
    if (!(t[k] > t[k - 1]))
      return mpm_err_set(err, MPM_EINVAL, "jam: frame %zu at t = %g s is not after frame %zu "
                         "(t = %g s)", k, t[k], k - 1, t[k - 1]);
    if (npoints[k] > npoints[k - 1])
      return mpm_err_set(err, MPM_EINVAL, "jam: frame %zu has %zu points, more than the "
                         "%zu of frame %zu", k, npoints[k], npoints[k - 1], k - 1);
  }
  const double t0 = t[0], te = t[nf - 1], span = te - t0;
  out->t_end = te;
  out->t_zero = NAN;
  double tp = 0.0, vp = 0.0;                       /* last usable sample */
  int have = 0;
  for (size_t k = 0; k < nf; k++) {
    const double v = vbar[k];
    if (!isfinite(v) || v == 0.0)
      continue;
    if (have && (v > 0.0) != (vp > 0.0))
      out->t_zero = tp + (t[k] - tp) * vp / (vp - v);  /* linear: vbar = 0 there */
    tp = t[k];
    vp = v;
    have = 1;
  }
  if (isfinite(out->t_zero) && out->t_zero >= t0 + 0.9 * span)
    out->v_vote = MPM_JAM_STATIC;
  else if (!isfinite(out->t_zero) || out->t_zero < t0 + 0.5 * span)
    out->v_vote = MPM_JAM_FLOWING;
  else
    out->v_vote = MPM_JAM_UNSURE;
  size_t left = 0;
  int frames = 0;
  for (size_t k = 1; k < nf; k++)
    if (t[k] >= t0 + 0.9 * span) {
      left += npoints[k - 1] - npoints[k];
      frames++;
    }
  out->frames = frames;
  out->leaving = (double)left / frames;            /* frames >= 1: the last one counts */
  out->n_vote = out->leaving <= 1.0 ? MPM_JAM_STATIC
                : out->leaving > 10.0 ? MPM_JAM_FLOWING : MPM_JAM_UNSURE;
  out->cls = out->v_vote == out->n_vote ? out->v_vote : MPM_JAM_UNSURE;
  return MPM_OK;
}
