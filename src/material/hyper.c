/* hyper.c: the hyperelastic trans-phase nonlocal granular fluidity point
 * update of [HS21] §3, Algorithm 1 (MODEL.md section 7), with the local
 * fluidity solve of MODEL.md section 5 step 4 (ngf.c) reused as it is.
 *
 * One step dt with L (L_ij = d v_i / d x_j) fixed, per point:
 *   F_{n+1} = (I + dt L) F_n,  J = det F_{n+1},  Fe_tr = F_{n+1} Fp_n^-1 = Re Ue,
 *   Ee = ln Ue,  Me_tr = 2G dev(Ee) + K tr(Ee) I,  p = -tr(Me_tr)/3 = -K tr(Ee),
 *   tau_tr = |dev Me_tr| / sqrt(2)  (the tau of mpm_sym3_tau),
 *   Np = dev(Me_tr) / |dev Me_tr|.
 * States:
 *   rho_{n+1} < rho_c or p <= 0: stress-free, sigma = 0, g = 0,
 *     gdot_p = sqrt(2 D0:D0) (as the 2D models), Fp_{n+1} = F_{n+1};
 *   p_n <= 0 (stress-free before, now dense): g = sqrt(2 D0:D0) / mu_2  [HS21 eq. 23];
 *   p_n > 0: g* = max(0, g_n + (dt/t0) A^2 d^2 lap), g = the root of the
 *     section 5 quadratic with p, tau_tr, g*, mu_n g_n
 *     (mpm_material_ngf_gstar, mpm_material_ngf_fluidity; [HS21] eq. 24 is its
 *     explicit cousin, the semi-implicit form is the one of the 2D code);
 *   then tau = tau_tr p / (p + G dt g),  Me = Me_tr - sqrt(2) (tau_tr - tau) Np,
 *   sigma = J^-1 Re Me Re^T,  gdot_p = g tau / p = (tau_tr - tau) / (G dt),
 *   Lp = gdot_p Np / sqrt(2),  Fp_{n+1} = exp(dt Lp) Fp_n          [eq. 25-31].
 *
 * Choices, where MODEL.md section 7 or [HS21] leave room or read otherwise:
 * - F_{n+1} = (I + dt L) F_n: dF/dt = L F for the spatial gradient L of this
 *   code. MODEL.md and [HS21] eq. 18 write F_n (I + dt L), which is the same
 *   update for the transposed gradient (L_ij = d v_j / d x_i); with this
 *   code's L it would stretch a body that has turned along its material axes
 *   instead of the spatial ones (tests/test_hyper.c, t_F_update_order).
 * - Fp_{n+1} = exp(dt Lp) Fp_n: Lp = dFp/dt Fp^-1 lives, with Me and Np, in
 *   the intermediate configuration. Then Fe_{n+1} = Fe_tr exp(-dt Lp), and
 *   since Np is coaxial with Ue_tr (Me_tr is an isotropic function of Ee),
 *   Re is unchanged and Ee_{n+1} = Ee_tr - dt Lp exactly: the stored state
 *   (F, Fp) gives back the returned Me, so nothing drifts from step to step.
 *   The exponential instead of I + dt Lp ([HS21] eq. 31, MODEL.md) keeps
 *   det Fp = exp(dt tr Lp) det Fp_n = det Fp_n, tr Np = 0 (plastic flow is
 *   isochoric); the forward-Euler factor would change det Fp by O(dt^2).
 * - gdot_p = g tau / p, the friction mu_{n+1} = tau/p of the return, also in
 *   the step that reconnects ([HS21] uses mu_2 there): the plastic flow is
 *   then exactly the deviatoric stress removed, G dt gdot_p = tau_tr - tau,
 *   which the consistency above needs.
 * - The reconnecting fluidity uses the deviatoric rate, sqrt(2 D0:D0) / mu_2
 *   ([HS21] writes sqrt(2)|D|; equal for isochoric D): plastic flow is
 *   isochoric, and sqrt(2 D0:D0) is the gdot_p of a stress-free point
 *   (mpm_material_mu_i_gdp), so gdot_p = g mu_2 is continuous across
 *   reconnection as in the 2D models.
 * - Stress-free points take Fp_{n+1} = F_{n+1} ([HS21] Algorithm 1), i.e.
 *   Fe = I: a grain that separates keeps no elastic strain, and when it is
 *   caught again it starts from its stress-free natural state instead of the
 *   stretched one it left. Fp then carries the volume change (det Fp = J at
 *   the last separation), and sigma divides Re Me Re^T by J = det F as
 *   [HS21] eq. 27.
 * - det F <= 0 (an inverted point, or non-finite F) gives a NaN stress, a
 *   physical failure for the caller to report, never a stress-free state.
 *
 * Eigen-decomposition, logarithm and polar decomposition. Everything is
 * computed from the eigenpairs (mu_i, v_i) of C - I = Fe^T Fe - I, formed
 * from H = Fe - I as H + H^T + H^T H, by cyclic Jacobi rotations:
 *   Ue = V diag(sqrt(1 + mu)) V^T,  Ee = V diag(log1p(mu)/2) V^T,
 *   Re V = Fe V diag(1 / sqrt(1 + mu))  (Re = Fe Ue^-1, never formed alone).
 * Why this route: (1) C does not see the rotation (R^T R = I), so a rotation
 * of any size, 179 or 180 degrees included, costs no accuracy, unlike
 * rotation-angle formulas; (2) Fe is near a rotation in granular flow (small
 * elastic strain), where C - I is small: taken from H instead of C, and with
 * log1p, the strain keeps its relative accuracy as it goes to zero, and
 * (3) Jacobi rotations give eigenvectors orthonormal to round-off even for
 * equal or nearly equal eigenvalues (the near-identity case), where the
 * closed-form (trigonometric) 3x3 eigenvalues lose accuracy and the
 * eigenvectors from cross products break down; the cyclic method converges
 * quadratically, a few sweeps for 3x3. A Higham (Newton) polar iteration
 * would give Re well, but the Hencky strain needs the eigenvectors anyway.
 * The cost: C squares the condition number, so Re is orthogonal to about
 * eps cond(Fe)^2, which for elastic stretches of a few percent is eps. */
#include "material/hyper.h"

#include <float.h>
#include <math.h>

#include "core/points.h"

enum { JACOBI_SWEEPS = 32 };   /* a 3x3 needs a few sweeps; the cap only bounds a bad input */

/* The off-diagonal planes (p, q) of a cyclic sweep. */
static const int jacobi_planes[3][2] = {{0, 1}, {0, 2}, {1, 2}};

/* One Jacobi rotation in the plane (p, q) that zeroes a[p][q], accumulated
 * into the columns of v: a <- J^T a J, v <- v J with J_pp = J_qq = c,
 * J_pq = -J_qp = s, t = s/c the smaller root of t^2 + 2 theta t - 1 = 0,
 * theta = (a_qq - a_pp) / (2 a_pq). sqrt(1 + theta^2) is |theta| itself in
 * double above 1e150 (where theta^2 would overflow), so no hypot is needed. */
static void jacobi_rotate(double a[3][3], mpm_mat3 *v, int p, int q)
{
  const double apq = a[p][q];
  const double theta = (a[q][q] - a[p][p]) / (2.0 * apq), at = fabs(theta);
  const double root = at < 1e150 ? sqrt(1.0 + at * at) : at;      /* sqrt(1 + theta^2) */
  const double t = copysign(1.0 / (at + root), theta);
  const double c = 1.0 / sqrt(1.0 + t * t), s = t * c;
  const double h = s / (1.0 + c);                                  /* tan(angle/2) */
  a[p][p] -= t * apq;                                              /* a_pp - t a_pq */
  a[q][q] += t * apq;                                              /* a_qq + t a_pq */
  a[p][q] = a[q][p] = 0.0;
  const int r = 3 - p - q;                                         /* the third index */
  const double arp = a[r][p], arq = a[r][q];
  a[r][p] = a[p][r] = arp - s * (arq + h * arp);                   /* c a_rp - s a_rq */
  a[r][q] = a[q][r] = arq + s * (arp - h * arq);                   /* s a_rp + c a_rq */
  for (int k = 0; k < 3; k++) {
    const double vp = v->m[k][p], vq = v->m[k][q];
    v->m[k][p] = vp - s * (vq + h * vp);
    v->m[k][q] = vq + s * (vp - h * vq);
  }
}

/* Cyclic Jacobi on the symmetric a (destroyed): a = v diag(lam) v^T. An
 * off-diagonal entry is dropped when it is below eps/2 of the geometric mean
 * of its two diagonal entries (it then moves no eigenvalue by more than
 * round-off relative to itself), so graded and near-zero matrices keep their
 * relative accuracy; the sweeps end when a whole sweep rotates nothing. */
static void jacobi(double a[3][3], double lam[3], mpm_mat3 *v)
{
  *v = mpm_mat3_identity();
  for (int sweep = 0; sweep < JACOBI_SWEEPS; sweep++) {
    int rotated = 0;
    for (int k = 0; k < 3; k++) {
      const int p = jacobi_planes[k][0], q = jacobi_planes[k][1];
      const double apq = a[p][q];
      if (apq == 0.0)
        continue;
      if (fabs(apq) <= 0.5 * DBL_EPSILON * sqrt(fabs(a[p][p])) * sqrt(fabs(a[q][q]))) {
        a[p][q] = a[q][p] = 0.0;                                   /* negligible */
        continue;
      }
      if (!isfinite(apq))
        break;                                                     /* NaN/inf in: no loop */
      jacobi_rotate(a, v, p, q);
      rotated = 1;
    }
    if (!rotated)
      break;
  }
  for (int i = 0; i < 3; i++)
    lam[i] = a[i][i];
}

static mpm_sym3 sym3_diag(const double d[3])
{
  return (mpm_sym3){d[0], d[1], d[2], 0.0, 0.0, 0.0};
}

void mpm_material_hyper_eigen(mpm_sym3 a, double lam[3], mpm_mat3 *v)
{
  mpm_mat3 w = mpm_sym3_full(a);
  jacobi(w.m, lam, v);
}

mpm_sym3 mpm_material_hyper_log(mpm_sym3 a)
{
  double lam[3];
  mpm_mat3 v;
  mpm_material_hyper_eigen(mpm_sym3_add_iso(a, -1.0), lam, &v);   /* a - I = v diag(lam) v^T */
  for (int i = 0; i < 3; i++)
    lam[i] = log1p(lam[i]);                                        /* ln(1 + lam) */
  return mpm_sym3_congruence(&v, sym3_diag(lam));
}

mpm_sym3 mpm_material_hyper_exp(mpm_sym3 a)
{
  double lam[3];
  mpm_mat3 v;
  mpm_material_hyper_eigen(a, lam, &v);
  for (int i = 0; i < 3; i++)
    lam[i] = expm1(lam[i]);                                        /* exp(lam) - 1 */
  return mpm_sym3_add_iso(mpm_sym3_congruence(&v, sym3_diag(lam)), 1.0);
}

/* The eigenpairs of C - I, C = f^T f, formed from h = f - I as
 * h + h^T + h^T h: f = r v diag(sqrt(1 + mu)) v^T. */
static void stretch_eigen(const mpm_mat3 *f, double mu[3], mpm_mat3 *v)
{
  mpm_mat3 h = *f;
  for (int i = 0; i < 3; i++)
    h.m[i][i] -= 1.0;                                              /* h = f - I */
  double c[3][3];
  for (int i = 0; i < 3; i++)
    for (int j = i; j < 3; j++) {
      double hh = h.m[0][i] * h.m[0][j] + h.m[1][i] * h.m[1][j] + h.m[2][i] * h.m[2][j];
      c[i][j] = c[j][i] = h.m[i][j] + h.m[j][i] + hh;              /* (h + h^T + h^T h)_ij */
    }
  jacobi(c, mu, v);
}

/* f v diag(d): the columns of f v scaled. */
static mpm_mat3 mul_scale_cols(const mpm_mat3 *f, const mpm_mat3 *v, const double d[3])
{
  mpm_mat3 w = mpm_mat3_mul(f, v);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      w.m[i][j] *= d[j];
  return w;
}

void mpm_material_hyper_polar(const mpm_mat3 *f, mpm_mat3 *r, mpm_sym3 *u)
{
  double mu[3], su[3], iu[3];
  mpm_mat3 v;
  stretch_eigen(f, mu, &v);
  for (int i = 0; i < 3; i++) {
    su[i] = sqrt(1.0 + mu[i]);                                     /* principal stretches */
    iu[i] = 1.0 / su[i];
  }
  *u = mpm_sym3_congruence(&v, sym3_diag(su));                     /* U = V diag(s) V^T */
  mpm_mat3 rv = mul_scale_cols(f, &v, iu);                         /* R V = F V diag(1/s) */
  mpm_mat3 vt = mpm_mat3_transpose(&v);
  *r = mpm_mat3_mul(&rv, &vt);                                     /* R = (R V) V^T */
}

/* The trial state of Fe = F Fp^-1 in the principal frame of Ue. */
typedef struct hyper_trial {
  double J;        /* det F */
  mpm_mat3 v;      /* V: principal directions of Ue (intermediate configuration) */
  mpm_mat3 rv;     /* Re V: the same directions in the current configuration */
  double e0[3];    /* dev(Ee), principal */
  double s0[3];    /* dev(Me_tr) = 2G dev(Ee), principal */
  double p;        /* p = -K tr(Ee) */
  double tau;      /* tau_tr = |dev Me_tr| / sqrt(2) */
} hyper_trial;

static hyper_trial hyper_trial_of(const mpm_material_params *par, const mpm_mat3 *F,
                                  const mpm_mat3 *Fp)
{
  hyper_trial t;
  mpm_mat3 Fpi = mpm_mat3_inverse(Fp);
  mpm_mat3 Fe = mpm_mat3_mul(F, &Fpi);                             /* Fe_tr = F Fp^-1 */
  double mu[3], e[3], iu[3];
  stretch_eigen(&Fe, mu, &t.v);
  for (int i = 0; i < 3; i++) {
    e[i] = 0.5 * log1p(mu[i]);                                     /* Ee = ln sqrt(1 + mu) */
    iu[i] = 1.0 / sqrt(1.0 + mu[i]);
  }
  t.rv = mul_scale_cols(&Fe, &t.v, iu);                            /* Re V = Fe V diag(1/s) */
  t.J = mpm_mat3_det(F);
  const double tr = e[0] + e[1] + e[2], m = tr / 3.0;
  double ss = 0.0;
  for (int i = 0; i < 3; i++) {
    t.e0[i] = e[i] - m;                                            /* dev(Ee) */
    t.s0[i] = 2.0 * par->G * t.e0[i];                              /* 2G dev(Ee) */
    ss += t.s0[i] * t.s0[i];
  }
  t.p = -par->K * tr;                                              /* -tr(Me)/3 */
  t.tau = sqrt(0.5 * ss);                                          /* |dev Me| / sqrt(2) */
  return t;
}

/* sigma = J^-1 Re Me Re^T for Me = -p I + r dev(Me_tr) (principal in V);
 * NaN if J <= 0. */
static mpm_sym3 hyper_cauchy(const hyper_trial *t, double r)
{
  if (!(t->J > 0.0)) {
    const double n = NAN;
    return (mpm_sym3){n, n, n, n, n, n};
  }
  double me[3];
  for (int i = 0; i < 3; i++)
    me[i] = (r * t->s0[i] - t->p) / t->J;                          /* J^-1 Me, principal */
  return mpm_sym3_congruence(&t->rv, sym3_diag(me));              /* (Re V) diag (Re V)^T */
}

/* F_{n+1} = (I + dt L) F_n. */
static mpm_mat3 hyper_advance(const mpm_mat3 *L, double dt, const mpm_mat3 *F)
{
  mpm_mat3 A = mpm_mat3_identity();
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      A.m[i][j] += dt * L->m[i][j];
  return mpm_mat3_mul(&A, F);
}

mpm_sym3 mpm_material_hyper_stress(const mpm_material_params *par, const mpm_mat3 *F,
                                   const mpm_mat3 *Fp)
{
  hyper_trial t = hyper_trial_of(par, F, Fp);
  return hyper_cauchy(&t, 1.0);
}

mpm_mat3 mpm_material_hyper_F_of_stress(const mpm_material_params *par, mpm_sym3 sigma)
{
  /* Fe = Ue = exp(Ee) coaxial with sigma, Re = I: Me = J sigma, so
   * Ee = J dev(sigma) / 2G + (ln J / 3) I with J = exp(tr Ee) the root of
   * ln J = J s, s = tr(sigma) / 3K (Newton from J = 1; for compression
   * s < 0 the root is unique and Newton converges from there) */
  const double sv = mpm_sym3_trace(sigma) / (3.0 * par->K);
  double J = 1.0;
  for (int k = 0; k < 50; k++) {
    const double step = (log(J) - J * sv) / (1.0 / J - sv);
    J -= step;
    if (!(J > 0.0) || fabs(step) <= 1e-16 * J)
      break;
  }
  mpm_mat3 F;
  if (!(J > 0.0) || !isfinite(J)) {                   /* no elastic state: NaN */
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++)
        F.m[i][j] = NAN;
    return F;
  }
  const mpm_sym3 Ee = mpm_sym3_add_iso(mpm_sym3_scale(mpm_sym3_dev(sigma), J / (2.0 * par->G)),
                                       log(J) / 3.0);
  const mpm_sym3 U = mpm_material_hyper_exp(Ee);
  const double u[3][3] = {{U.xx, U.xy, U.zx}, {U.xy, U.yy, U.yz}, {U.zx, U.yz, U.zz}};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      F.m[i][j] = u[i][j];
  return F;
}

mpm_material_hyper_point mpm_material_hyper_elastic_step(const mpm_material_params *par,
                                                         const mpm_mat3 *L, double dt,
                                                         mpm_material_hyper_point pt)
{
  pt.F = hyper_advance(L, dt, &pt.F);
  pt.sigma = mpm_material_hyper_stress(par, &pt.F, &pt.Fp);
  pt.g = 0.0;
  pt.gdp = 0.0;
  pt.state = MPM_STATE_DENSE;
  return pt;
}

mpm_material_hyper_point mpm_material_hyper_step(const mpm_material_params *par,
                                                 const mpm_mat3 *L, double dt,
                                                 mpm_material_hyper_point pt)
{
  const mpm_sym3 D = mpm_mat3_sym(L);
  const double p_n = mpm_sym3_pressure(pt.sigma);
  const int was_dense = p_n > 0.0;
  const double g_n = was_dense ? pt.g : 0.0;
  const double mug_n = was_dense ? g_n * mpm_sym3_tau(pt.sigma) / p_n : 0.0;  /* mu_n g_n */
  pt.F = hyper_advance(L, dt, &pt.F);                              /* F_{n+1} */
  hyper_trial t = hyper_trial_of(par, &pt.F, &pt.Fp);
  if (!(t.J > 0.0)) {                                              /* inverted: a failure */
    pt.sigma = hyper_cauchy(&t, 1.0);
    return pt;
  }
  const double gfree = mpm_material_mu_i_gdp(par, mpm_sym3_zero(), D, MPM_STATE_DISCONNECTED);
  if (!(pt.rho >= par->rho_c) || !(t.p > 0.0)) {                  /* stress-free */
    pt.sigma = mpm_sym3_zero();
    pt.Fp = pt.F;                                                  /* Fe = I */
    pt.g = 0.0;
    pt.gdp = gfree;                                                /* sqrt(2 D0:D0) */
    pt.state = MPM_STATE_DISCONNECTED;
    return pt;
  }
  double g;
  if (!was_dense)
    g = gfree / par->mu_2;                                         /* reconnects: [HS21] eq. 23 */
  else {
    const double gs = mpm_material_ngf_gstar(par, dt, g_n, pt.lap);                /* g* */
    g = mpm_material_ngf_fluidity(par, dt, t.p, t.tau, gs, mug_n, pt.isp);        /* g_{n+1} */
  }
  const double r = mpm_material_ngf_return_ratio(par, dt, t.p, g); /* tau / tau_tr */
  const double w = r * (par->G * dt * g) / t.p;                    /* 1 - r, no cancellation */
  pt.sigma = hyper_cauchy(&t, r);                                  /* Me = -p I + r dev Me_tr */
  pt.g = g;
  pt.gdp = g * r * t.tau / t.p;                                    /* g tau / p */
  /* dt Lp = dt gdot_p Np / sqrt(2) = (1 - r) dev(Ee): principal values
   * w e0_i in V (G dt gdot_p = tau_tr - tau = (1 - r) tau_tr). */
  double x[3];
  for (int i = 0; i < 3; i++)
    x[i] = exp(w * t.e0[i]);
  mpm_sym3 expl = mpm_sym3_congruence(&t.v, sym3_diag(x));         /* exp(dt Lp) */
  mpm_mat3 E = mpm_sym3_full(expl);
  pt.Fp = mpm_mat3_mul(&E, &pt.Fp);                                /* Fp_{n+1} = exp(dt Lp) Fp_n */
  pt.state = MPM_STATE_DENSE;
  return pt;
}

/* The parameters of the NGF model, checked as the plane NGF checks them. */
static int ngf_hyper_check(const mpm_material_params *par, mpm_err *err)
{
  return mpm_material_ngf.check(par, err);
}

/* The model's updates: the step of each point as it is (its eigen-
 * decompositions iterate; no loop over points vectorises them), point by
 * point over a batch. */
static void ngf_hyper_update_point(const mpm_material_params *par, const mpm_mat3 *L,
                                   double dt, mpm_mpoint *pt, mpm_mdeform *def)
{
  mpm_material_hyper_point h = {.F = def->F, .Fp = def->Fp, .sigma = pt->sigma, .rho = pt->rho,
                                .g = pt->g, .lap = pt->lap, .isp = pt->isp, .gdp = pt->gdp,
                                .state = pt->state};
  h = mpm_material_hyper_step(par, L, dt, h);
  *pt = (mpm_mpoint){.sigma = h.sigma, .rho = h.rho, .g = h.g, .lap = h.lap, .isp = h.isp,
                     .gdp = h.gdp, .state = h.state};
  *def = (mpm_mdeform){.F = h.F, .Fp = h.Fp};
}

static void ngf_hyper_update(const mpm_material_params *par, double dt, int nsub,
                             const mpm_material_batch *b)
{
  const int D = b->dim, ns = D == 3 ? 6 : 4;
  for (size_t q = 0; q < b->n; q++) {
    mpm_mat3 L = {{{0.0}}};
    for (int i = 0; i < D; i++)
      for (int j = 0; j < D; j++)
        L.m[i][j] = b->L[D * i + j][q];
    double s[6] = {0.0};
    for (int k = 0; k < ns; k++)
      s[k] = b->sig[k][q];
    mpm_material_hyper_point h = {.sigma = {s[0], s[1], s[2], s[3], s[4], s[5]}, .rho = b->rho[q],
                                  .g = b->g[q], .lap = b->lap ? b->lap[q] : 0.0,
                                  .isp = b->isp ? b->isp[q] : 0.0, .gdp = b->gdp[q],
                                  .state = b->state[q]};
    for (int e = 0; e < 9; e++) {
      h.F.m[e / 3][e % 3] = b->F[e][q];
      h.Fp.m[e / 3][e % 3] = b->Fp[e][q];
    }
    for (int k = 0; k < nsub; k++) {
      if (D == 2)                 /* plane strain: the stress out of the plane is zero */
        h.sigma.yz = h.sigma.zx = 0.0;
      h = mpm_material_hyper_step(par, &L, dt, h);
    }
    const double out[6] = {h.sigma.xx, h.sigma.yy, h.sigma.zz, h.sigma.xy, h.sigma.yz,
                           h.sigma.zx};
    for (int k = 0; k < ns; k++)
      b->sig[k][q] = out[k];
    b->g[q] = h.g;
    b->gdp[q] = h.gdp;
    b->state[q] = h.state;
    for (int e = 0; e < 9; e++) {
      b->F[e][q] = h.F.m[e / 3][e % 3];
      b->Fp[e][q] = h.Fp.m[e / 3][e % 3];
    }
  }
}

const mpm_material_type mpm_material_ngf_hyper = {
  .name = "ngf_hyper",
  .description = "hyperelastic nonlocal granular fluidity, F = Fe Fp with Hencky strain and "
                 "Mandel stress, the NGF local solve and diffusion of g [HS21]",
  .check = ngf_hyper_check,
  .update = ngf_hyper_update,
  .update_point = ngf_hyper_update_point,
  .defgrad = 1,
  .nonlocal = 1,
  .dense = mpm_material_ngf_dense,
};
