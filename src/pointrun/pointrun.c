/* pointrun.c: one material point under a prescribed history: the discrete
 * update run step by step (pointrun.h; MODEL.md section 4).
 *
 * Step k: L_k from the history (default: exact mean over the step),
 *   rho_{k+1} = rho_k exp(-dt tr L_k)          (MODEL.md section 2 step 5),
 *   sigma_{k+1}, gdot_p from the model with rho_{k+1}.
 * The steps are t_k = t_0 + k dt; if dt does not divide the history's length
 * the last step ends at its end and is shorter. */
#include "pointrun/pointrun.h"

#include <math.h>
#include <string.h>

#include "core/points.h"
#include "material/hyper.h"

/* Names of enum mpm_sample, in its order. */
static const char *const sample_names[] = {"mean", "start", "mid", "end"};

int mpm_pointrun_sample_from_name(const char *name)
{
  for (int i = 0; i < (int)(sizeof sample_names / sizeof sample_names[0]); i++)
    if (strcmp(name, sample_names[i]) == 0)
      return i;
  return -1;
}

/* ------------------------------------------------------- the discrete run */

int mpm_pointrun_init_state(const mpm_material_params *par, const mpm_point_init *init)
{
  return init->rho >= par->rho_c && mpm_sym3_pressure(init->sigma) > 0.0
             ? MPM_STATE_DENSE : MPM_STATE_DISCONNECTED;
}

size_t mpm_pointrun_steps(const mpm_history *h, double dt)
{
  double T = mpm_pointrun_history_t_end(h) - mpm_pointrun_history_t_begin(h);
  double q = T / dt, r = nearbyint(q);
  if (fabs(q - r) <= 1e-9 * (r > 1.0 ? r : 1.0))
    return r > 1.0 ? (size_t)r : 1;                            /* dt divides T */
  return (size_t)ceil(q);                                      /* last step shorter */
}

/* Time of row k of a run with nsteps steps of dt. */
static double row_time(const mpm_history *h, double dt, size_t k, size_t nsteps)
{
  return k == nsteps ? mpm_pointrun_history_t_end(h)
                     : mpm_pointrun_history_t_begin(h) + (double)k * dt;
}

static mpm_mat3 sample_L(const mpm_history *h, double a, double b, int sample)
{
  switch (sample) {
  case MPM_SAMPLE_START: return mpm_pointrun_history_eval(h, a);
  case MPM_SAMPLE_MID: return mpm_pointrun_history_eval(h, 0.5 * (a + b));
  case MPM_SAMPLE_END: return mpm_pointrun_history_eval(h, b);
  default: return mpm_pointrun_history_mean(h, a, b);
  }
}

int mpm_pointrun_update(const mpm_material_type *mt, const mpm_material_params *par,
                        const mpm_history *h, const mpm_point_init *init, double dt,
                        int sample, mpm_series **out, mpm_err *err)
{
  *out = NULL;
  if (!(dt > 0.0) || !isfinite(dt))
    return mpm_err_set(err, MPM_EINVAL, "time step dt = %g: must be > 0", dt);
  size_t nsteps = mpm_pointrun_steps(h, dt);
  mpm_series *s = mpm_pointrun_series_alloc(nsteps + 1);
  if (!s)
    return mpm_err_set(err, MPM_ENOMEM, "out of memory for %zu steps", nsteps);
  mpm_mpoint pt = {.sigma = init->sigma, .rho = init->rho};
  mpm_mdeform def = {.Fp = {{{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}}}};
  if (mt->defgrad)                            /* the elastic state of the initial stress */
    def.F = mpm_material_hyper_F_of_stress(par, init->sigma);
  int st0 = mpm_pointrun_init_state(par, init);
  mpm_mat3 L0 = mpm_pointrun_history_eval(h, mpm_pointrun_history_t_begin(h));
  mpm_sym3 D = mpm_mat3_sym(&L0);
  s->t[0] = mpm_pointrun_history_t_begin(h);
  double gdp0 = mpm_material_mu_i_gdp(par, init->sigma, D, st0);
  mpm_pointrun_series_record(s, 0, &(mpm_point_rec){init->sigma, init->rho, gdp0, st0, D});
  for (size_t k = 0; k < nsteps; k++) {
    double a = row_time(h, dt, k, nsteps), b = row_time(h, dt, k + 1, nsteps);
    mpm_mat3 L = sample_L(h, a, b, sample);
    pt.rho *= exp(-(b - a) * mpm_mat3_trace(&L));            /* rho_{k+1} */
    mt->update_point(par, &L, b - a, &pt, &def);
    s->t[k + 1] = b;
    mpm_pointrun_series_record(s, k + 1, &(mpm_point_rec){pt.sigma, pt.rho, pt.gdp, pt.state,
                                                          mpm_mat3_sym(&L)});
  }
  *out = s;
  return MPM_OK;
}
