/* health.c: a run whose state stops being a state is reported as what it
 * is, before it shows up as something else (a point "leaving the mesh" at
 * (nan, nan), far away, or a run that "finishes" with g = inf): the point,
 * the field and its value, the time, and the likely cause.
 *
 * Three tests. After every (sub)step's update, on each chunk of points while
 * it is at hand (mpm_sim_updated_bad), every field the update and the move
 * wrote: the stresses, the volume, the plastic shear rate, and as the run
 * has them the fluidity g, F and Fp, the convected extents (CPDI1) and the
 * affine matrix (APIC); their sum is finite unless one of them is not (or is
 * beyond 1e300 in magnitude, absurd for any field), the volume positive, and
 * |g| dt at most MPM_SIM_G_DT_MAX (below). After every step the point speeds
 * (a non-finite velocity or one that carries a point more than a mesh unit
 * per step, |v| dt > min(dx, dy) (and dz on boxes), where MPM no longer
 * holds: the stencil, and so the mapping, assume a point stays near its
 * unit). On any failure, and when a test trips, every field of every point
 * (mpm_sim_check_state): the extents (convected under CPDI1, where a
 * blown-up extent is the origin), the stresses (the usual origin), then
 * volume, fluidity, plastic shear rate, F, Fp, the affine matrix, velocity,
 * position.
 *
 * The bound on g: the fluidity relaxes the shear stress of a dense point
 * (tau = tau_tr p / (G dt g + p)), and the return caps the plastic shear of
 * a step at the elastic one, so a stable NGF run keeps g dt near tau / (G mu)
 * or below, far below 1 (about 3e-5 in the V7 chute and the V10 silo);
 * |g| dt > 1e3 is a field that is blowing up (an unstable explicit diffusion
 * of g grows it by a factor each substep), not a flow. */
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

static void find_cause(const mpm_sim *s, const char *given, char *buf, size_t len)
{
  if (given)
    snprintf(buf, len, "%s", given);
  else
    likely_cause(s, buf, len);
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

/* The magnitude beyond which a value of any field is absurd: the sum of the
 * fields of a point (at most 24) cannot overflow below it. */
static const double ABSURD = 1e300;

double mpm_sim_g_max(const mpm_sim *s)
{
  return MPM_SIM_G_DT_MAX / s->dt;
}

/* 1 if the sum over k < NV of v[k][p] is not finite for a p of [a, b): NV a
 * constant (4 or 9, a tensor's components in the plane or in 3D), so that
 * the sum is unrolled and the loop over the points vectorises. */
#define SUM_BAD(NV)                                                                   \
  static int sum##NV##_bad(const double *const *v, size_t a, size_t b)                \
  {                                                                                   \
    int bad = 0;                                                                      \
    for (size_t p = a; p < b; p++) {                                                  \
      double t = 0.0;                                                                 \
      for (int k = 0; k < NV; k++)                                                    \
        t += v[k][p];                                                                 \
      bad |= !(t - t == 0.0);                                                         \
    }                                                                                 \
    return bad;                                                                       \
  }
SUM_BAD(4)
SUM_BAD(9)
#undef SUM_BAD

/* The D x D components of a tensor field t[i][j] bad somewhere in [a, b). */
static int tensor_bad(double *const t[3][3], int D, size_t a, size_t b)
{
  const double *v[9];
  int nv = 0;
  for (int i = 0; i < D; i++)
    for (int j = 0; j < D; j++)
      v[nv++] = t[i][j];
  return D == 3 ? sum9_bad(v, a, b) : sum4_bad(v, a, b);
}

int mpm_sim_updated_bad(const mpm_sim *s, size_t a, size_t b)
{
  const mpm_points *P = s->pts;
  const double *const s0 = P->sxx, *const s1 = P->syy, *const s2 = P->szz, *const s3 = P->sxy;
  const double *const vol = P->vol, *const gdp = P->gdp;
  int bad = 0;                  /* one pass that vectorises; a NaN fails every test */
  if (s->dim == 3) {
    const double *const s4 = P->syz, *const s5 = P->szx;
    for (size_t p = a; p < b; p++) {
      const double t = s0[p] + s1[p] + s2[p] + s3[p] + s4[p] + s5[p] + vol[p] + gdp[p];
      bad |= !(t - t == 0.0) | !(vol[p] > 0.0);
    }
  } else {
    for (size_t p = a; p < b; p++) {
      const double t = s0[p] + s1[p] + s2[p] + s3[p] + vol[p] + gdp[p];
      bad |= !(t - t == 0.0) | !(vol[p] > 0.0);
    }
  }
  if (s->mat->nonlocal) {
    const double *const g = P->g, gmax = mpm_sim_g_max(s);
    for (size_t p = a; p < b; p++)
      bad |= !(fabs(g[p]) <= gmax);
  }
  if (bad)
    return 1;
  const int D = s->dim;
  if (P->defgrad && (tensor_bad(P->F, 3, a, b) || tensor_bad(P->Fp, 3, a, b)))
    return 1;
  if (s->shape->convect && tensor_bad(P->ext, D, a, b))
    return 1;
  return s->cfg.time.transfer == MPM_TRANSFER_APIC && tensor_bad(P->aff, D, a, b);
}

/* A field of the point store, for the diagnosis. */
typedef struct field {
  const char *name, *unit, *what;
  const double *v;
} field;

/* What is wrong with value x of field f at a point, or NULL: not finite,
 * absurd, not positive (a volume), or (g) beyond the bound of the banner. */
static const char *wrong(const mpm_sim *s, const field *f, double x, char *buf, size_t len)
{
  if (!isfinite(x))
    return "not finite";
  if (f->v == s->pts->vol && !(x > 0.0))
    return "not positive";
  if (f->v == s->pts->g && !(fabs(x) <= mpm_sim_g_max(s))) {
    snprintf(buf, len, "absurd: |g| dt = %.3g > %g with dt = %.3g s (a stable run keeps it "
             "far below 1)", fabs(x) * s->dt, MPM_SIM_G_DT_MAX, s->dt);
    return buf;
  }
  if (fabs(x) > ABSURD) {
    snprintf(buf, len, "absurd: beyond %g in magnitude", ABSURD);
    return buf;
  }
  return NULL;
}

/* mpm_sim_check_state with the cause given (NULL: the likely cause of a
 * blow-up). */
static int check_state(const mpm_sim *s, double t, const char *given, mpm_err *err)
{
  const mpm_points *P = s->pts;
  const field fields[] = {   /* F, Fp and the 3D fields are NULL in a store without them */
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
    {"plastic shear rate gdot_p", "1/s", "plastic shear rate", P->gdp},
    {"F xx", "", "deformation gradient", P->fxx},
    {"F xy", "", "deformation gradient", P->fxy},
    {"F xz", "", "deformation gradient", P->fxz},
    {"F yx", "", "deformation gradient", P->fyx},
    {"F yy", "", "deformation gradient", P->fyy},
    {"F yz", "", "deformation gradient", P->fyz},
    {"F zx", "", "deformation gradient", P->fzx},
    {"F zy", "", "deformation gradient", P->fzy},
    {"F zz", "", "deformation gradient", P->fzz},
    {"Fp xx", "", "plastic deformation gradient", P->fpxx},
    {"Fp xy", "", "plastic deformation gradient", P->fpxy},
    {"Fp xz", "", "plastic deformation gradient", P->fpxz},
    {"Fp yx", "", "plastic deformation gradient", P->fpyx},
    {"Fp yy", "", "plastic deformation gradient", P->fpyy},
    {"Fp yz", "", "plastic deformation gradient", P->fpyz},
    {"Fp zx", "", "plastic deformation gradient", P->fpzx},
    {"Fp zy", "", "plastic deformation gradient", P->fpzy},
    {"Fp zz", "", "plastic deformation gradient", P->fpzz},
    {"affine matrix cxx", "1/s", "affine velocity matrix", P->cxx},
    {"affine matrix cxy", "1/s", "affine velocity matrix", P->cxy},
    {"affine matrix cxz", "1/s", "affine velocity matrix", P->cxz},
    {"affine matrix cyx", "1/s", "affine velocity matrix", P->cyx},
    {"affine matrix cyy", "1/s", "affine velocity matrix", P->cyy},
    {"affine matrix cyz", "1/s", "affine velocity matrix", P->cyz},
    {"affine matrix czx", "1/s", "affine velocity matrix", P->czx},
    {"affine matrix czy", "1/s", "affine velocity matrix", P->czy},
    {"affine matrix czz", "1/s", "affine velocity matrix", P->czz},
    {"velocity vx", "m/s", "velocity", P->vx}, {"velocity vy", "m/s", "velocity", P->vy},
    {"velocity vz", "m/s", "velocity", P->vz},
    {"position x", "m", "position", P->x},  {"position y", "m", "position", P->y},
    {"position z", "m", "position", P->z},
  };
  char cause[MPM_ERR_MSG / 2], at[96], why[160];
  for (size_t k = 0; k < sizeof fields / sizeof fields[0]; k++)
    for (size_t p = 0; fields[k].v && p < P->n; p++) {
      const char *w = wrong(s, &fields[k], fields[k].v[p], why, sizeof why);
      if (!w)
        continue;
      find_cause(s, given, cause, sizeof cause);
      return mpm_err_set(err, MPM_ENONFINITE,
                         "point %d: %s = %g%s%s at %s m, t = %.6g s: the %s is %s; "
                         "likely cause: %s", P->id[p], fields[k].name, fields[k].v[p],
                         fields[k].unit[0] ? " " : "", fields[k].unit,
                         position(P, p, at, sizeof at), t, fields[k].what, w, cause);
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
  find_cause(s, given, cause, sizeof cause);
  return mpm_err_set(err, MPM_ENONFINITE,
                     "point %d: speed %.3g m/s at %s m, t = %.6g s: a runaway, more "
                     "than a mesh unit per step (min(%s) / dt = %.3g m/s; P-wave and fill "
                     "speed of the input %.3g m/s); likely cause: %s", P->id[fast], vmax,
                     position(P, fast, at, sizeof at), t, s->dim == 3 ? "dx, dy, dz" : "dx, dy",
                     lim, h / mpm_sim_stable_dt(&s->cfg), cause);
}

int mpm_sim_check_state(const mpm_sim *s, double t, mpm_err *err)
{
  return check_state(s, t, NULL, err);
}

int mpm_sim_check_restored(const mpm_sim *s, mpm_err *err)
{
  return check_state(s, s->t, "a damaged checkpoint, or one written by a run that was already "
                     "going wrong", err);
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
