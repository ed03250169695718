/* reference.c: the mu(I) constitutive ODE of [DK15] eq. 2.15 for one point,
 * integrated with GSL's embedded Runge-Kutta-Fehlberg 4(5) (rkf45) at tight
 * tolerance: the reference of verification case V2 ([DK15] App. B).
 *
 * Dense:  dsigma/dt = C:(D - Dp) + W sigma - sigma W,  drho/dt = -rho tr D,
 *         Dp = gdot_p sigma0 / (2 tau),  gdot_p = xi sqrt(p) (mu - mu_s)/(mu_2 - mu)
 *         for mu_s < mu < mu_2, 0 for mu <= mu_s  (eq. 2.12-2.13 inverted).
 * Since tr Dp = 0 and tr(W s - s W) = 0, dp/dt = -K tr D and d ln rho/dt = -tr D:
 * on a history segment (tr D linear in t) both are quadratics in time, so every
 * change of regime is located exactly by a quadratic root:
 *   DISC  (sigma = 0)       -> LAYER when rho >= rho_c and tr D < 0 (the trial
 *                              pressure of the update would be > 0);
 *   LAYER (0 <= p < p_floor) -> DENSE at p = p_floor, -> DISC at p = 0 or rho = rho_c;
 *   DENSE                    -> LAYER at p = p_floor / 2 (hysteresis, so that
 *                               round-off cannot make the two switch back and
 *                               forth), -> DISC at rho = rho_c.
 * In LAYER the deviator, bounded by mu_2 p < mu_2 p_floor, is dropped and
 * Dp = D0: the p -> 0+ limit, where the ODE becomes infinitely stiff (its
 * relaxation rate grows like p^(-3/2)) and an explicit integrator cannot follow.
 * DENSE is integrated with gsl_odeiv2_driver_apply from output time to output
 * time; the driver is reset at every entry into DENSE. History nodes (kinks of
 * L) are always stopping points, so the right-hand side is smooth in each call. */
#include "pointrun/reference.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_odeiv2.h>
#include <math.h>
#include <stdlib.h>

#include "core/points.h"

enum ref_mode { REF_DENSE, REF_LAYER, REF_DISC };
enum { REF_DIM = 5 };  /* sxx, syy, szz, sxy, rho */

typedef struct ref_ctx {
  const mpm_material_params *par;
  const mpm_history *h;
  const mpm_reference_opts *o;
  size_t seg;               /* history segment used by the right-hand side */
  int mode;                 /* enum ref_mode */
  double t;
  double y[REF_DIM];
  gsl_odeiv2_driver *drv;
  double hstart;            /* first step after a reset [s] */
} ref_ctx;

void mpm_pointrun_reference_defaults(const mpm_material_params *par, mpm_reference_opts *o)
{
  o->rtol = 1e-10;
  o->atol = 1e-9;
  o->p_floor = 1e-10 * par->K;
  o->max_steps = 10000000UL;
}

static mpm_sym3 y_sigma(const double *y)
{
  return (mpm_sym3){y[0], y[1], y[2], y[3], 0.0, 0.0};
}

static void set_iso(double *y, double p)  /* sigma = -p I */
{
  y[0] = y[1] = y[2] = -p;
  y[3] = 0.0;
}

/* Right-hand side in DENSE; GSL_EDOM (step retried smaller) outside 0 < p, mu < mu_2. */
static int ref_rhs(double t, const double y[], double f[], void *params)
{
  const ref_ctx *c = params;
  const mpm_material_params *par = c->par;
  mpm_mat3 L = mpm_pointrun_history_eval_seg(c->h, c->seg, t);
  mpm_sym3 D = mpm_mat3_sym(&L), s = y_sigma(y), s0 = mpm_sym3_dev(s);
  mpm_mat3 W = mpm_mat3_skw(&L);
  double p = mpm_sym3_pressure(s), tau = sqrt(0.5 * mpm_sym3_ddot(s0, s0));
  if (!(p > 0.0) || !(tau < par->mu_2 * p))
    return GSL_EDOM;
  double mu = tau / p;
  double gdp = mu > par->mu_s
                   ? par->xi * sqrt(p) * (mu - par->mu_s) / (par->mu_2 - mu) : 0.0;
  mpm_sym3 Dp = tau > 0.0 ? mpm_sym3_scale(s0, gdp / (2.0 * tau)) : mpm_sym3_zero();
  mpm_sym3 rate = mpm_sym3_add(mpm_sym3_elastic(mpm_sym3_axpy(D, -1.0, Dp), par->G, par->K),
                               mpm_sym3_spin(&W, s));      /* C:(D - Dp) + W s - s W */
  f[0] = rate.xx;
  f[1] = rate.yy;
  f[2] = rate.zz;
  f[3] = rate.xy;
  f[4] = -y[4] * mpm_sym3_trace(D);                          /* drho/dt = -rho tr D */
  return GSL_SUCCESS;
}

/* ------------------------------------------------------ regime changes */

/* Smallest s in (0, T] where f(s) = f0 + f1 s + f2 s^2 crosses zero in direction
 * dir (+1 rising, -1 falling); -1 if none. Roots by the stable formula, so a
 * root at s = 0 (f0 = 0) comes out as exactly 0 and is excluded. */
static double first_crossing(double f0, double f1, double f2, double T, int dir)
{
  double r[2];
  int nr = 0;
  if (f2 == 0.0) {
    if (f1 != 0.0)
      r[nr++] = -f0 / f1;
  } else {
    double disc = f1 * f1 - 4.0 * f2 * f0;
    if (disc < 0.0)
      return -1.0;
    double q = -0.5 * (f1 + copysign(sqrt(disc), f1));    /* no cancellation */
    r[nr++] = q / f2;
    if (q != 0.0)
      r[nr++] = f0 / q;
  }
  if (nr == 2 && r[1] < r[0]) {
    double tmp = r[0];
    r[0] = r[1];
    r[1] = tmp;
  }
  for (int i = 0; i < nr; i++) {
    double slope = f1 + 2.0 * f2 * r[i];                     /* f'(root) */
    if (r[i] > 0.0 && r[i] <= T && slope * dir > 0.0)
      return r[i];
  }
  return -1.0;
}

/* Earlier of two candidate event offsets (-1 = none). */
static double earlier(double a, double b)
{
  if (a < 0.0)
    return b;
  if (b < 0.0)
    return a;
  return a < b ? a : b;
}

/* tr D on the current segment as c0 + c1 s, s = time since c->t. */
static void trD_line(const ref_ctx *c, double *c0, double *c1)
{
  const mpm_history *h = c->h;
  size_t k = c->seg;
  const double *a = h->L + 4 * k, *b = a + 4;
  *c1 = ((b[0] + b[3]) - (a[0] + a[3])) / (h->t[k + 1] - h->t[k]);
  mpm_mat3 L = mpm_pointrun_history_eval_seg(h, k, c->t);
  *c0 = mpm_mat3_trace(&L);
}

/* Offset of the next regime change within (0, T], -1 if none; *next = new mode.
 * With I(s) = c0 s + c1 s^2 / 2: p(s) = p - K I(s), ln(rho(s)/rho_c) = q - I(s). */
static double next_event(const ref_ctx *c, double T, int *next)
{
  double c0, c1, K = c->par->K;
  trD_line(c, &c0, &c1);
  double p = mpm_sym3_pressure(y_sigma(c->y)), q = log(c->y[4] / c->par->rho_c);
  double pf = c->o->p_floor, s_up, s_down;
  switch (c->mode) {
  case REF_DISC:
    if (q >= 0.0 && (c0 < 0.0 || (c0 == 0.0 && c1 < 0.0))) {
      *next = REF_LAYER;                                       /* reconnect now */
      return 0.0;
    }
    s_up = first_crossing(q, -c0, -0.5 * c1, T, +1);           /* rho rises past rho_c */
    if (q >= 0.0 && c1 < 0.0 && c0 >= 0.0) {                   /* tr D turns negative */
      double sz = -c0 / c1;
      if (sz > 0.0 && sz <= T && q - (c0 * sz + 0.5 * c1 * sz * sz) >= 0.0)
        s_up = earlier(s_up, sz);
    }
    *next = REF_LAYER;
    return s_up;
  case REF_LAYER:
    if (q < 0.0 || (p <= 0.0 && !(c0 < 0.0 || (c0 == 0.0 && c1 < 0.0)))) {
      *next = REF_DISC;
      return 0.0;
    }
    if (p >= pf) {
      *next = REF_DENSE;
      return 0.0;
    }
    s_up = first_crossing(p - pf, -K * c0, -0.5 * K * c1, T, +1);
    s_down = earlier(first_crossing(p, -K * c0, -0.5 * K * c1, T, -1),
                     first_crossing(q, -c0, -0.5 * c1, T, -1));
    *next = (s_up >= 0.0 && (s_down < 0.0 || s_up < s_down)) ? REF_DENSE : REF_DISC;
    return earlier(s_up, s_down);
  default:
    if (q < 0.0) {
      *next = REF_DISC;
      return 0.0;
    }
    if (p < 0.5 * pf) {                                        /* hysteresis: leave at pf/2 */
      *next = REF_LAYER;
      return 0.0;
    }
    s_down = first_crossing(p - 0.5 * pf, -K * c0, -0.5 * K * c1, T, -1);
    s_up = first_crossing(q, -c0, -0.5 * c1, T, -1);           /* rho falls below rho_c */
    *next = (s_up >= 0.0 && (s_down < 0.0 || s_up < s_down)) ? REF_DISC : REF_LAYER;
    return earlier(s_down, s_up);
  }
}

/* Switch regime at the current time. The quantity that defined the switch is
 * set to its threshold (rho = rho_c on reconnection, p = p_floor on entering
 * DENSE), so that round-off in the closed forms cannot undo the switch. */
static void enter_mode(ref_ctx *c, int mode)
{
  double p = mpm_sym3_pressure(y_sigma(c->y));
  if (mode == REF_DISC) {
    set_iso(c->y, 0.0);                                        /* sigma = 0 */
  } else if (mode == REF_LAYER) {
    set_iso(c->y, p > 0.0 ? p : 0.0);                          /* deviator dropped */
    if (c->mode == REF_DISC && c->y[4] < c->par->rho_c)
      c->y[4] = c->par->rho_c;                                 /* reconnected at rho_c */
  } else {
    if (c->mode == REF_LAYER && p < c->o->p_floor)
      set_iso(c->y, c->o->p_floor);
    gsl_odeiv2_driver_reset_hstart(c->drv, c->hstart);
  }
  c->mode = mode;
}

/* Advance over s in DISC or LAYER: sigma = -p(s) I, rho(s) analytic. */
static void advance_closed_form(ref_ctx *c, double s)
{
  double c0, c1;
  trD_line(c, &c0, &c1);
  double I = c0 * s + 0.5 * c1 * s * s;                        /* int tr D */
  double p = mpm_sym3_pressure(y_sigma(c->y));
  c->y[4] *= exp(-I);                                          /* rho */
  set_iso(c->y, c->mode == REF_LAYER ? p - c->par->K * I : 0.0);
  c->t += s;
}

static int advance_dense(ref_ctx *c, double t1, mpm_err *err)
{
  int st = gsl_odeiv2_driver_apply(c->drv, &c->t, t1, c->y);
  if (st != GSL_SUCCESS)
    return mpm_err_set(err, MPM_ESOLVE, "reference ODE (rkf45) failed at t = %.17g s: %s",
                       c->t, gsl_strerror(st));
  return MPM_OK;
}

/* Advance from c->t to t1, both in one history segment. */
static int advance(ref_ctx *c, double t1, mpm_err *err)
{
  c->seg = mpm_pointrun_history_segment(c->h, 0.5 * (c->t + t1));
  for (int guard = 0; c->t < t1; guard++) {
    if (guard > 64)
      return mpm_err_set(err, MPM_ESOLVE, "reference ODE: regime changes do not settle "
                         "at t = %.17g s", c->t);
    int next = c->mode;
    double s = next_event(c, t1 - c->t, &next);
    if (s == 0.0) {
      enter_mode(c, next);
      continue;
    }
    double te = (s > 0.0 && s < t1 - c->t) ? c->t + s : t1;
    if (c->mode == REF_DENSE) {
      int rc = advance_dense(c, te, err);
      if (rc != MPM_OK)
        return rc;
    } else {
      advance_closed_form(c, te - c->t);
    }
    c->t = te;
    if (s > 0.0)
      enter_mode(c, next);
  }
  return MPM_OK;
}

/* Record the state at the current time into row k. */
static void record(const ref_ctx *c, mpm_series *out, size_t k)
{
  mpm_mat3 L = mpm_pointrun_history_eval(c->h, c->t);
  mpm_sym3 D = mpm_mat3_sym(&L), sigma = y_sigma(c->y);
  int state = c->mode == REF_DISC ? MPM_STATE_DISCONNECTED : MPM_STATE_DENSE;
  int gdp_state = c->mode == REF_DENSE ? state : MPM_STATE_DISCONNECTED;  /* LAYER: D0 */
  double gdp = mpm_material_mu_i_gdp(c->par, sigma, D, gdp_state);
  mpm_pointrun_series_record(out, k, &(mpm_point_rec){sigma, c->y[4], gdp, state, D});
}

static int initial_mode(ref_ctx *c, const mpm_point_init *init, mpm_err *err)
{
  const mpm_material_params *par = c->par;
  mpm_sym3 s = init->sigma;
  double p = mpm_sym3_pressure(s);
  c->y[0] = s.xx;
  c->y[1] = s.yy;
  c->y[2] = s.zz;
  c->y[3] = s.xy;
  c->y[4] = init->rho;
  if (s.yz != 0.0 || s.zx != 0.0)
    return mpm_err_set(err, MPM_EINVAL, "reference ODE: initial stress must be plane (yz = zx = 0)");
  if (!(init->rho > 0.0))
    return mpm_err_set(err, MPM_EINVAL, "reference ODE: initial density %g must be > 0",
                       init->rho);
  if (mpm_pointrun_init_state(par, init) == MPM_STATE_DISCONNECTED) {
    enter_mode(c, REF_DISC);
  } else if (p < c->o->p_floor) {
    enter_mode(c, REF_LAYER);
  } else {
    if (!(mpm_sym3_tau(s) < par->mu_2 * p))
      return mpm_err_set(err, MPM_EINVAL, "reference ODE: initial stress has mu = %g >= mu_2 = %g "
                         "(no finite plastic rate)", mpm_sym3_tau(s) / p, par->mu_2);
    enter_mode(c, REF_DENSE);
  }
  return MPM_OK;
}

/* Integrate to every output time, stopping at every history node on the way. */
static int ref_sweep(ref_ctx *c, mpm_series *out, mpm_err *err)
{
  const mpm_history *h = c->h;
  size_t node = 1;
  record(c, out, 0);
  for (size_t k = 1; k < out->n; k++) {
    if (!(out->t[k] > out->t[k - 1]) || out->t[k] > mpm_pointrun_history_t_end(h))
      return mpm_err_set(err, MPM_EINVAL, "reference ODE: output time %zu (%.17g s) is not "
                         "increasing or lies beyond the history", k, out->t[k]);
    while (node < h->n && h->t[node] <= out->t[k]) {
      if (h->t[node] > c->t) {
        int rc = advance(c, h->t[node], err);
        if (rc != MPM_OK)
          return rc;
      }
      node++;
    }
    if (out->t[k] > c->t) {
      int rc = advance(c, out->t[k], err);
      if (rc != MPM_OK)
        return rc;
    }
    record(c, out, k);
  }
  return MPM_OK;
}

int mpm_pointrun_reference_run(const mpm_material_params *par, const mpm_history *h,
                               const mpm_point_init *init, const mpm_reference_opts *o,
                               mpm_series *out, mpm_err *err)
{
  if (out->n == 0 || out->t[0] < mpm_pointrun_history_t_begin(h))
    return mpm_err_set(err, MPM_EINVAL, "reference ODE: no output times inside the history");
  ref_ctx c = {.par = par, .h = h, .o = o, .t = out->t[0], .mode = -1};  /* set below */
  c.hstart = 1e-9 * (mpm_pointrun_history_t_end(h) - mpm_pointrun_history_t_begin(h));
  gsl_odeiv2_system sys = {ref_rhs, NULL, REF_DIM, &c};
  c.drv = gsl_odeiv2_driver_alloc_y_new(&sys, gsl_odeiv2_step_rkf45, c.hstart, o->atol, o->rtol);
  if (!c.drv)
    return mpm_err_set(err, MPM_ENOMEM, "reference ODE: out of memory");
  gsl_odeiv2_driver_set_nmax(c.drv, o->max_steps);
  /* GSL's default handler aborts the process; report failures as codes instead. */
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  int rc = initial_mode(&c, init, err);
  if (rc == MPM_OK)
    rc = ref_sweep(&c, out, err);
  gsl_set_error_handler(old);
  gsl_odeiv2_driver_free(c.drv);
  return rc;
}
