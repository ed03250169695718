/* health.c: a run whose state stops being a state is reported as what it
 * is, before it shows up as something else (a point "leaving the mesh" at
 * (nan, nan), far away): the point, the field and its value, the time, and
 * the likely cause.
 *
 * Two tests: after every step the point speeds (cheap: a non-finite
 * velocity or one that carries a point more than a mesh unit per step,
 * |v| dt > min(dx, dy) (and dz on boxes), where MPM no longer holds: the stencil, and so the
 * mapping, assume a point stays near its unit); on any failure, and when a
 * speed trips, every field of every point: the extents (convected under
 * CPDI1, where a blown-up extent is the origin), the stresses (the usual
 * origin), then volume, fluidity, velocity, position. */
#include "solver/solver.h"

#include <math.h>
#include <stdio.h>

/* The likely cause of a blow-up, for the message. */
static void likely_cause(const mpm_sim *s, char *buf, size_t len)
{
  const double st = mpm_sim_stable_dt(&s->cfg);
  mpm_err e = {0};
  const mpm_nonlocal_diffusion *d =
      s->nl && mpm_nonlocal_diffusion_name(s->cfg.material.diffusion)
          ? mpm_nonlocal_diffusion_table[s->cfg.material.diffusion]
          : NULL;
  if (s->dt > st * (1.0 + 1e-9))
    snprintf(buf, len, "the time step: dt = %.3g s is %.3g times the stable step %.3g s "
             "(key 'time.dt', allowed only with time.dt_unstable_ok)", s->dt, s->dt / st, st);
  else if (d && d->stability_limited &&
           mpm_material_ngf_check_diffusion(&s->par, s->dt, s->n_sub, s->mesh.dx, s->mesh.dy,
                                            s->dim == 3 ? s->mesh.dz : 0.0, &e) != MPM_OK)
    snprintf(buf, len, "the diffusion of g: %.200s (key 'material.n_sub')", e.msg);
  else
    snprintf(buf, len, "a material parameter or a boundary condition (key 'material.*'; the "
             "step dt = %.3g s is within the stable %.3g s)", s->dt, st);
}

/* The smallest side of a mesh unit. */
static double unit_size(const mpm_sim *s)
{
  double h = fmin(s->mesh.dx, s->mesh.dy);
  return s->dim == 3 ? fmin(h, s->mesh.dz) : h;
}

/* "(x, y)" or "(x, y, z)" of point p, for a message. */
static const char *position(const mpm_points *P, size_t p, char *buf, size_t len)
{
  if (P->z)
    snprintf(buf, len, "(%.6g, %.6g, %.6g)", P->x[p], P->y[p], P->z[p]);
  else
    snprintf(buf, len, "(%.6g, %.6g)", P->x[p], P->y[p]);
  return buf;
}

/* A field of the point store, for the diagnosis. */
typedef struct field {
  const char *name, *unit, *what;
  const double *v;
} field;

int mpm_sim_check_state(const mpm_sim *s, double t, mpm_err *err)
{
  const mpm_points *P = s->pts;
  const field fields[] = {
    /* extents first: fixed (uGIMP) they stay finite; convected (CPDI1) a
     * blown-up extent makes the weights, and then the stress, non-finite */
    {"extent r1x", "m", "extent", P->r1x},  {"extent r1y", "m", "extent", P->r1y},
    {"extent r2x", "m", "extent", P->r2x},  {"extent r2y", "m", "extent", P->r2y},
    {"extent r1z", "m", "extent", P->r1z},  {"extent r2z", "m", "extent", P->r2z},
    {"extent r3x", "m", "extent", P->r3x},  {"extent r3y", "m", "extent", P->r3y},
    {"extent r3z", "m", "extent", P->r3z},
    {"stress sxx", "Pa", "stress", P->sxx}, {"stress syy", "Pa", "stress", P->syy},
    {"stress szz", "Pa", "stress", P->szz}, {"stress sxy", "Pa", "stress", P->sxy},
    {"stress syz", "Pa", "stress", P->syz}, {"stress szx", "Pa", "stress", P->szx},
    {"volume", s->dim == 3 ? "m^3" : "m^2", "volume", P->vol},
    {"fluidity g", "1/s", "fluidity", P->g},
    {"velocity vx", "m/s", "velocity", P->vx}, {"velocity vy", "m/s", "velocity", P->vy},
    {"velocity vz", "m/s", "velocity", P->vz},
    {"position x", "m", "position", P->x},  {"position y", "m", "position", P->y},
    {"position z", "m", "position", P->z},
  };
  char cause[MPM_ERR_MSG / 2], at[96];
  for (size_t k = 0; k < sizeof fields / sizeof fields[0]; k++)
    for (size_t p = 0; fields[k].v && p < P->n; p++) {   /* a 3D field is NULL in 2D */
      if (isfinite(fields[k].v[p]) && (fields[k].v != P->vol || fields[k].v[p] > 0.0))
        continue;
      likely_cause(s, cause, sizeof cause);
      return mpm_err_set(err, MPM_ENONFINITE,
                         "point %d: %s = %g %s at %s m, t = %.6g s: the %s is %s; "
                         "likely cause: %s", P->id[p], fields[k].name, fields[k].v[p],
                         fields[k].unit, position(P, p, at, sizeof at), t, fields[k].what,
                         isfinite(fields[k].v[p]) ? "not positive" : "not finite", cause);
    }
  const double h = unit_size(s), lim = h / s->dt;
  size_t fast = P->n;
  double vmax = 0.0;
  for (size_t p = 0; p < P->n; p++) {
    const double v = hypot(hypot(P->vx[p], P->vy[p]), P->vz ? P->vz[p] : 0.0);
    if (v > lim && v > vmax) {
      vmax = v;
      fast = p;
    }
  }
  if (fast == P->n)
    return MPM_OK;
  likely_cause(s, cause, sizeof cause);
  return mpm_err_set(err, MPM_ENONFINITE,
                     "point %d: speed %.3g m/s at %s m, t = %.6g s: a runaway, more "
                     "than a mesh unit per step (min(%s) / dt = %.3g m/s; P-wave and fill "
                     "speed of the input %.3g m/s); likely cause: %s", P->id[fast], vmax,
                     position(P, fast, at, sizeof at), t, s->dim == 3 ? "dx, dy, dz" : "dx, dy",
                     lim, h / mpm_sim_stable_dt(&s->cfg), cause);
}

int mpm_sim_too_fast(const mpm_sim *s, size_t a, size_t b)
{
  const mpm_points *P = s->pts;
  const double h = unit_size(s), lim2 = (h / s->dt) * (h / s->dt);
  int bad = 0;
  if (s->dim == 3)
    for (size_t p = a; p < b; p++)
      bad |= !(P->vx[p] * P->vx[p] + P->vy[p] * P->vy[p] + P->vz[p] * P->vz[p] <= lim2);
  else
    for (size_t p = a; p < b; p++)
      bad |= !(P->vx[p] * P->vx[p] + P->vy[p] * P->vy[p] <= lim2);  /* NaN fails too */
  return bad;
}

int mpm_sim_check_speeds(const mpm_sim *s, double t, mpm_err *err)
{
  const int bad = (s->scan & MPM_SIM_SCAN_FAST) && mpm_sim_too_fast(s, 0, s->pts->n);
  return bad ? mpm_sim_check_state(s, t, err) : MPM_OK;
}
