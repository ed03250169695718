/* ngf1d.c: steady 1D nonlocal granular fluidity by finite volumes and
 * pseudo-transient Newton (see ngf1d.h for the equations).
 *
 * Discretisation: l^2 (flux_{i+1/2} - flux_{i-1/2}) = int_cell (local part),
 * flux_{i+1/2} = kap_{i+1/2} (g_{i+1} - g_i), vertex-centred cells, half cells
 * at the ends, zero flux at a Neumann end, g = 0 at a Dirichlet end.
 *   chute: with s = H xi^2 (depth), l^2 g_ss = R becomes
 *            l^2 d/dxi (g_xi / xi) = 4 H^2 xi R,
 *          and xi R = P xi g + Q g^2 xi / sqrt(p) (p = p_top + kappa H xi^2,
 *          kappa = rho grav cos(theta)) is smooth in xi although g_ss ~ s^-1/2
 *          when p_top = 0: kap_{i+1/2} = 2/(xi_{i+1}^2 - xi_i^2) (exact for
 *          g = a + b xi^2), local part 4 H^2 (P g int xi + Q g^2 int xi/sqrt(p))
 *          over the cell, the integrals exact
 *          (int xi/sqrt(p) dxi = sqrt(p)/(kappa H)).
 *   vchute: uniform x, kap = 1/h, local part |cell| (P g + Q g^2/sqrt(p)),
 *          or for the kk equation |cell| |P| (g - g_loc).
 *   annulus: uniform r; l^2 (g'' + g'/r) = R times r is l^2 (r g')' = r R, so
 *          kap_{i+1/2} = 1/ln(r_{i+1}/r_i) (the flux r g' exact for
 *          g = a + c ln r, the radial analogue of the chute's choice), local
 *          part int r R over the cell (Gauss, split at kinks as below), pseudo
 *          mass int r dr; zero flux (g' = 0) at both walls; omega by the
 *          trapezoid rule on gdot/r from omega(R_o) = 0. A = 0: g = g_loc at
 *          the nodes (the local model), no equation solved.
 * Residual F_i = l^2 (kap_{i+1/2}(g_{i+1}-g_i) - kap_{i-1/2}(g_i-g_{i-1}))
 *              - c1_i g_i - c2_i g_i^2 + c0_i; Jacobian J symmetric tridiagonal
 * (the kk equation is linear: c2 = 0, and the first Newton step solves it).
 * Pseudo time: M dg/dtau = F(g), implicit Euler linearised once per step,
 *   (M/dtau - J) delta = F, g <- max(g + delta, 0),
 * with dtau kept small enough that M/dtau - J is positive definite (the step
 * is then a stable implicit step, which cannot flip a growing mode's sign and
 * so cannot fall onto g = 0 when g = 0 is unstable), and grown geometrically
 * (switched evolution relaxation) so that it ends in Newton's method. */
#define _DEFAULT_SOURCE /* M_PI */
#include "ngf1d.h"

#include <gsl/gsl_errno.h>
#include <gsl/gsl_linalg.h>
#include <gsl/gsl_roots.h>
#include <gsl/gsl_vector.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

/* Discrete problem. */
typedef struct grid {
  int n, nu;        /* intervals, unknowns (g_0 .. g_{nu-1}) */
  double l2;        /* (A d)^2 [m^2] */
  double *kap;      /* [n] face i+1/2 */
  double *c1, *c2;  /* [n+1] local part c1 g + c2 g^2 ... */
  double *c0;       /* [n+1] ... - c0 (the kk equation's source) */
  double *mass;     /* [n+1] pseudo-time mass */
  double *pos, *mu; /* [n+1] */
  double *vw;       /* [n+1] velocity: dv = gdot vw d(index) (trapezoid weights) */
} grid;

static void grid_free(grid *G)
{
  free(G->kap);
  free(G->c1);
  free(G->c2);
  free(G->c0);
  free(G->mass);
  free(G->pos);
  free(G->mu);
  free(G->vw);
}

static int grid_alloc(grid *G, int n)
{
  G->n = n;
  size_t m = (size_t)n + 1;
  G->kap = calloc(m, sizeof(double));
  G->c1 = calloc(m, sizeof(double));
  G->c2 = calloc(m, sizeof(double));
  G->c0 = calloc(m, sizeof(double));
  G->mass = calloc(m, sizeof(double));
  G->pos = calloc(m, sizeof(double));
  G->mu = calloc(m, sizeof(double));
  G->vw = calloc(m, sizeof(double));
  if (!G->kap || !G->c1 || !G->c2 || !G->c0 || !G->mass || !G->pos || !G->mu || !G->vw) {
    grid_free(G);
    return -1;
  }
  return 0;
}

/* ---------------------------------------------------------------- model */

static double coef_P(const ngf1d_problem *pb, double mu)
{
  if (pb->form == NGF1D_HS21)
    return pb->mu_s - mu;                                        /* mu_s - mu */
  return (pb->mu_2 - pb->mu_s) * (pb->mu_s - mu) / (pb->mu_2 - mu);  /* dmu (mu_s-mu)/(mu_2-mu) */
}

static double coef_Q(const ngf1d_problem *pb, double mu)
{
  double b = (pb->mu_2 - pb->mu_s) / pb->I0;                     /* b = dmu / I0 */
  return b * sqrt(pb->rho_s) * pb->d * mu;                       /* b sqrt(rho_s d^2) mu */
}

/* Local inertial number at mu (A = 0): I0 (mu-mu_s)/(mu_2-mu) or (mu-mu_s)/b. */
static double local_I(const ngf1d_problem *pb, double mu)
{
  if (mu <= pb->mu_s)
    return 0.0;
  if (pb->form == NGF1D_HS21)
    return (mu - pb->mu_s) * pb->I0 / (pb->mu_2 - pb->mu_s);
  return pb->I0 * (mu - pb->mu_s) / (pb->mu_2 - mu);
}

/* Local fluidity g_loc = I_loc(mu) sqrt(p/(rho_s d^2)) / mu (0 for mu <= 0);
 * also -P sqrt(p)/Q, the nonzero root of the steady NGF equation's local part. */
static double local_g(const ngf1d_problem *pb, double mu)
{
  const double sp = sqrt(pb->p) / (pb->d * sqrt(pb->rho_s));     /* sqrt(p/(rho_s d^2)) */
  return mu > 0.0 ? local_I(pb, mu) * sp / mu : 0.0;
}

double ngf1d_mu(const ngf1d_problem *pb, double pos)
{
  if (pb->geometry == NGF1D_CHUTE)
    return tan(pb->theta);
  if (pb->geometry == NGF1D_VCHUTE)
    return pb->rho * pb->grav * fabs(pos) / pb->p;               /* rho grav |x| / p */
  double mu_i = pb->tau_i / pb->p;
  if (pb->r_step > 0.0)                                          /* test-only two zones */
    return pos < pb->r_step ? mu_i : pb->mu_out;
  return mu_i * (pb->Ri / pos) * (pb->Ri / pos);                 /* tau_i (R_i/r)^2 / p */
}

void ngf1d_defaults(ngf1d_problem *pb, int geometry)
{
  *pb = (ngf1d_problem){.geometry = geometry, .form = NGF1D_DK, .A = 0.25, .d = 0.005,
                        .mu_s = 0.3819, .mu_2 = 1.5, .I0 = 0.279, .rho_s = 2450.0,
                        .rho = 1500.0, .grav = 9.81, .theta = 27.0 * M_PI / 180.0,
                        .H = 0.0, .L = 1.0, .p = 900.0, .n = 400};
  if (geometry == NGF1D_CHUTE) {
    pb->H = 3.0 * ngf1d_hstop(pb);
  } else if (geometry == NGF1D_VCHUTE) {  /* [D-thesis] Table 4.1, mu = mu_s + b I, b = 0.9377 */
    pb->form = NGF1D_HS21;
    pb->A = 0.48;
    pb->d = 0.05;
    pb->mu_2 = 0.6435;
  } else {   /* Henann and Kamrin 2013's annular shear, same law (b = 0.9377) */
    pb->form = NGF1D_HS21;
    pb->equation = NGF1D_EQ_KK;
    pb->A = 0.48;
    pb->d = 0.001;
    pb->mu_2 = 0.6435;
    pb->p = 100.0;
    pb->Ri = 0.06;
    pb->Ro = 0.08;
    pb->Omega = 0.01;
    pb->tau_i = 0.0;
  }
}

int ngf1d_validate(const ngf1d_problem *pb, char *msg, size_t len)
{
  const char *bad = NULL;
  const int ann = pb->geometry == NGF1D_ANNULUS;
  if (!((pb->A > 0.0 || (ann && pb->A == 0.0)) && pb->d > 0.0 && pb->rho_s > 0.0 && pb->I0 > 0.0))
    bad = ann ? "A must be >= 0, d, rho_s and I0 > 0" : "A, d, rho_s and I0 must be > 0";
  else if (!(pb->mu_s >= 0.0 && pb->mu_2 > pb->mu_s))
    bad = "need 0 <= mu_s < mu_2";
  else if (!(pb->rho > 0.0 && pb->grav > 0.0) || pb->n < 4)
    bad = "rho and grav must be > 0 and n >= 4";
  else if (pb->geometry == NGF1D_CHUTE && !(pb->H > 0.0 && pb->theta > 0.0 &&
                                            pb->theta < M_PI / 2 && pb->p_top >= 0.0))
    bad = "chute: need H > 0, 0 < theta < 90 degrees and p_top >= 0";
  else if (pb->geometry == NGF1D_CHUTE && pb->form == NGF1D_DK && tan(pb->theta) >= pb->mu_2)
    bad = "chute, dk form: tan(theta) must be < mu_2 (no steady flow above)";
  else if (pb->equation == NGF1D_EQ_KK && pb->geometry == NGF1D_CHUTE)
    bad = "the kk equation is solved for the vertical chute and the annulus only";
  else if (pb->geometry == NGF1D_VCHUTE && !(pb->L > 0.0 && pb->p > 0.0))
    bad = "vchute: need L > 0 and p > 0";
  else if (pb->geometry == NGF1D_VCHUTE && pb->form == NGF1D_DK &&
           pb->rho * pb->grav * 0.5 * pb->L / pb->p >= pb->mu_2)
    bad = "vchute, dk form: the wall stress ratio rho grav L/(2p) must be < mu_2";
  else if (ann && !(pb->Ri > 0.0 && pb->Ro > pb->Ri && pb->p > 0.0 && pb->tau_i >= 0.0 &&
                    pb->Omega >= 0.0 && isfinite(pb->Ro) && isfinite(pb->tau_i)))
    bad = "annulus: need 0 < R_i < R_o, p > 0, tau_i >= 0 and Omega >= 0";
  else if (ann && pb->r_step > 0.0 && !(pb->r_step > pb->Ri && pb->r_step < pb->Ro &&
                                        pb->mu_out >= 0.0))
    bad = "annulus: the test zones need R_i < r_step < R_o and mu_out >= 0";
  else if (ann && pb->form == NGF1D_DK &&
           !(pb->tau_i < pb->mu_2 * pb->p && (pb->r_step <= 0.0 || pb->mu_out < pb->mu_2)))
    bad = "annulus, dk form: the stress ratio tau_i/p at the inner wall must be < mu_2";
  if (!bad)
    return 0;
  snprintf(msg, len, "%s", bad);
  return -1;
}

/* ---------------------------------------------------------------- grids */

/* Chute on xi = i/n (see banner). */
static void build_chute(const ngf1d_problem *pb, grid *G)
{
  const int n = G->n;
  const double h = 1.0 / n, mu = tan(pb->theta), H = pb->H;
  const double kH = pb->rho * pb->grav * cos(pb->theta) * H;      /* kappa H */
  const double P = coef_P(pb, mu), Q = coef_Q(pb, mu);
  for (int i = 0; i < n; i++)
    G->kap[i] = 2.0 / (h * h * (2.0 * i + 1.0));                  /* 2/(xi_{i+1}^2 - xi_i^2) */
  for (int i = 0; i <= n; i++) {
    double xi = i * h, lo = i == 0 ? 0.0 : xi - 0.5 * h, hi = i == n ? 1.0 : xi + 0.5 * h;
    double m = 0.5 * (hi * hi - lo * lo);                         /* int xi over the cell */
    double sq = (hi * hi - lo * lo) /                             /* (sqrt(p_hi) - sqrt(p_lo))/kH */
                (sqrt(pb->p_top + kH * hi * hi) + sqrt(pb->p_top + kH * lo * lo));
    G->c1[i] = 4.0 * H * H * P * m;
    G->c2[i] = 4.0 * H * H * Q * sq;                              /* int xi/sqrt(p) */
    G->mass[i] = 4.0 * H * H * m;
    G->pos[i] = H * (1.0 - xi * xi);                              /* z */
    G->mu[i] = mu;
    G->vw[i] = 2.0 * H * xi * h;                                  /* dz = 2 H xi dxi */
  }
  G->nu = n;                                                      /* g_n = 0 at the base */
}

/* Cell integrals of the local part over [lo, hi] with the geometry's weight w
 * (1 in the vertical chute, r in the annulus) and mu = ngf1d_mu(x):
 *   kk equation:  c1 = int w |P|, c0 = int w |P| g_loc, c2 = 0;
 *   NGF equation: c1 = int w P, c2 = int w Q / sqrt(p), c0 = 0.
 * The kk integrands have a kink at mu = mu_s (and the annulus' test zones a
 * jump at r_step), where the nodes fall anywhere: sampled at the node, a kink
 * costs the scheme its regular second-order error (the orders under refinement
 * scatter). So each cell is split there and each piece, smooth, integrated by
 * 4-point Gauss-Legendre. */
static const double gauss4_x[4] = {-0.8611363115940526, -0.3399810435848563,
                                   0.3399810435848563, 0.8611363115940526};
static const double gauss4_w[4] = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                   0.3478548451374538};

/* The position where the coefficients are not smooth (NAN if none). */
static double kink(const ngf1d_problem *pb)
{
  if (pb->geometry == NGF1D_CHUTE)
    return NAN;
  if (pb->geometry == NGF1D_VCHUTE)
    return pb->mu_s * pb->p / (pb->rho * pb->grav);               /* mu(x) = mu_s */
  if (pb->r_step > 0.0)
    return pb->r_step;                                             /* the zones' jump */
  double mu_i = pb->tau_i / pb->p;
  return mu_i > pb->mu_s ? pb->Ri * sqrt(mu_i / pb->mu_s) : NAN;  /* R_c: mu(R_c) = mu_s */
}

static void cell_coefs(const ngf1d_problem *pb, double lo, double hi, double *c1, double *c2,
                       double *c0)
{
  const double xc = kink(pb), isp = 1.0 / sqrt(pb->p);
  const double cut[3] = {lo, xc > lo && xc < hi ? xc : hi, hi};
  const int kk = pb->equation == NGF1D_EQ_KK, radial = pb->geometry == NGF1D_ANNULUS;
  *c1 = *c2 = *c0 = 0.0;
  for (int piece = 0; piece < 2; piece++) {
    double a = cut[piece], b = cut[piece + 1], half = 0.5 * (b - a), mid = 0.5 * (a + b);
    for (int q = 0; q < 4 && half > 0.0; q++) {
      double x = mid + half * gauss4_x[q], mu = ngf1d_mu(pb, x);
      double ww = half * gauss4_w[q] * (radial ? x : 1.0);        /* Gauss weight times w */
      if (kk) {
        double P = fabs(coef_P(pb, mu));
        *c1 += ww * P;                                             /* int w |P| */
        *c0 += ww * P * local_g(pb, mu);                           /* int w |P| g_loc */
      } else {
        *c1 += ww * coef_P(pb, mu);                                /* int w P */
        *c2 += ww * coef_Q(pb, mu) * isp;                          /* int w Q / sqrt(p) */
      }
    }
  }
}

/* Vertical chute on x = (L/2) i/n. */
static void build_vchute(const ngf1d_problem *pb, grid *G)
{
  const int n = G->n;
  const double h = 0.5 * pb->L / n, isp = 1.0 / sqrt(pb->p);
  for (int i = 0; i < n; i++)
    G->kap[i] = 1.0 / h;
  for (int i = 0; i <= n; i++) {
    double x = i * h, mu = pb->rho * pb->grav * x / pb->p;        /* mu = rho grav x / p */
    double w = (i == 0 || i == n) ? 0.5 * h : h;
    if (pb->equation == NGF1D_EQ_KK) {                            /* |P| (g - g_loc) */
      double lo = i == 0 ? 0.0 : x - 0.5 * h, hi = i == n ? x : x + 0.5 * h;
      cell_coefs(pb, lo, hi, &G->c1[i], &G->c2[i], &G->c0[i]);
    } else {
      G->c1[i] = coef_P(pb, mu) * w;
      G->c2[i] = coef_Q(pb, mu) * w * isp;
    }
    G->mass[i] = w;
    G->pos[i] = x;
    G->mu[i] = mu;
    G->vw[i] = h;
  }
  G->nu = pb->wall_neumann ? n + 1 : n;
}

/* Annulus on r_i = R_i + (R_o - R_i) i/n, both walls zero flux. */
static void build_annulus(const ngf1d_problem *pb, grid *G)
{
  const int n = G->n;
  const double h = (pb->Ro - pb->Ri) / n;
  for (int i = 0; i <= n; i++)
    G->pos[i] = i == n ? pb->Ro : pb->Ri + (pb->Ro - pb->Ri) * i / n;
  for (int i = 0; i < n; i++)
    G->kap[i] = 1.0 / log(G->pos[i + 1] / G->pos[i]);            /* 1/ln(r_{i+1}/r_i) */
  for (int i = 0; i <= n; i++) {
    double r = G->pos[i];
    double lo = i == 0 ? r : 0.5 * (G->pos[i - 1] + r), hi = i == n ? r : 0.5 * (r + G->pos[i + 1]);
    cell_coefs(pb, lo, hi, &G->c1[i], &G->c2[i], &G->c0[i]);     /* int r (local part) */
    G->mass[i] = 0.5 * (hi * hi - lo * lo);                       /* int r dr */
    G->mu[i] = ngf1d_mu(pb, r);
    G->vw[i] = h / r;                                             /* domega = gdot dr / r */
  }
  G->nu = n + 1;                                                  /* g' = 0 at both walls */
}

static int build(const ngf1d_problem *pb, grid *G)
{
  if (grid_alloc(G, pb->n))
    return -1;
  G->l2 = pb->A * pb->A * pb->d * pb->d;                          /* l^2 = (A d)^2 */
  if (pb->geometry == NGF1D_CHUTE)
    build_chute(pb, G);
  else if (pb->geometry == NGF1D_VCHUTE)
    build_vchute(pb, G);
  else
    build_annulus(pb, G);
  return 0;
}

/* ------------------------------------------------------- residual, Jacobian */

/* F (length nu) at g (n+1 entries, g[nu..n] = 0); returns max_i |F_i| / S_i,
 * S_i the sum of the magnitudes of the terms of F_i (0 where S_i = 0). */
static double residual(const grid *G, const double *g, double *F)
{
  double rmax = 0.0;
  for (int i = 0; i < G->nu; i++) {
    double kl = i > 0 ? G->kap[i - 1] : 0.0, kr = i < G->n ? G->kap[i] : 0.0;
    double gl = i > 0 ? g[i - 1] : 0.0, gr = i < G->n ? g[i + 1] : 0.0;
    double flux = G->l2 * (kr * (gr - g[i]) - kl * (g[i] - gl));  /* l^2 (q+ - q-) */
    F[i] = flux - G->c1[i] * g[i] - G->c2[i] * g[i] * g[i] + G->c0[i];
    double s = G->l2 * (kr * (fabs(gr) + fabs(g[i])) + kl * (fabs(g[i]) + fabs(gl)))
             + fabs(G->c1[i] * g[i]) + fabs(G->c2[i]) * g[i] * g[i] + fabs(G->c0[i]);
    double r = s > 0.0 ? fabs(F[i]) / s : 0.0;
    rmax = rmax > r ? rmax : r;
  }
  return rmax;
}

/* The tridiagonal (diag, off) of M/dtau - J, idtau = 1/dtau. */

static void system_matrix(const grid *G, const double *g, double idtau, double *diag,
                          double *off)
{
  for (int i = 0; i < G->nu; i++) {
    double kl = i > 0 ? G->kap[i - 1] : 0.0, kr = i < G->n ? G->kap[i] : 0.0;
    diag[i] = G->mass[i] * idtau + G->l2 * (kl + kr)              /* M/dtau - dF/dg_i */
            + G->c1[i] + 2.0 * G->c2[i] * g[i];
    if (i + 1 < G->nu)
      off[i] = -G->l2 * kr;
  }
}

/* 1 if the symmetric tridiagonal matrix is positive definite (LDL^T pivots). */
static int positive_definite(const double *diag, const double *off, int n)
{
  double piv = diag[0];
  if (!(piv > 0.0))
    return 0;
  for (int i = 1; i < n; i++) {
    piv = diag[i] - off[i - 1] * off[i - 1] / piv;
    if (!(piv > 0.0))
      return 0;
  }
  return 1;
}

/* ------------------------------------------------------------ the solver */

typedef struct work {
  double *F, *diag, *off, *delta, *gnew;
} work;

static void work_free(work *w)
{
  free(w->F);
  free(w->diag);
  free(w->off);
  free(w->delta);
  free(w->gnew);
}

static int work_alloc(work *w, int n)
{
  size_t m = (size_t)n + 1;
  w->F = calloc(m, sizeof(double));
  w->diag = calloc(m, sizeof(double));
  w->off = calloc(m, sizeof(double));
  w->delta = calloc(m, sizeof(double));
  w->gnew = calloc(m, sizeof(double));
  if (!w->F || !w->diag || !w->off || !w->delta || !w->gnew) {
    work_free(w);
    return -1;
  }
  return 0;
}

/* Solve the SPD tridiagonal system (diag, off) delta = F with GSL. */
static int solve_tridiag(work *w, int nu)
{
  gsl_vector_view d = gsl_vector_view_array(w->diag, (size_t)nu);
  gsl_vector_view e = gsl_vector_view_array(w->off, (size_t)nu - 1);
  gsl_vector_view b = gsl_vector_view_array(w->F, (size_t)nu);
  gsl_vector_view x = gsl_vector_view_array(w->delta, (size_t)nu);
  return gsl_linalg_solve_symm_tridiag(&d.vector, &e.vector, &b.vector, &x.vector);
}

static double max_of(const double *g, int n)
{
  double m = 0.0;
  for (int i = 0; i < n; i++)
    m = g[i] > m ? g[i] : m;
  return m;
}

/* One pseudo-time step from g into w->gnew; dtau is reduced until M/dtau - J
 * is positive definite. Returns 0, or -1 if no step size works. */
static int pseudo_step(const grid *G, const double *g, double *dtau, work *w)
{
  for (int tries = 0; tries < 200; tries++, *dtau *= 0.25) {
    system_matrix(G, g, 1.0 / *dtau, w->diag, w->off);
    if (!positive_definite(w->diag, w->off, G->nu))
      continue;
    residual(G, g, w->F);
    if (solve_tridiag(w, G->nu) != GSL_SUCCESS)
      continue;
    for (int i = 0; i <= G->n; i++) {
      double v = i < G->nu ? g[i] + w->delta[i] : 0.0;
      w->gnew[i] = v > 0.0 ? v : 0.0;                              /* g >= 0 */
    }
    return 0;
  }
  return -1;
}

/* Initial pseudo-time step: a thousandth of the smallest explicit scale. */
static double first_dtau(const grid *G)
{
  double t = INFINITY;
  for (int i = 0; i < G->nu; i++) {
    double kl = i > 0 ? G->kap[i - 1] : 0.0, kr = i < G->n ? G->kap[i] : 0.0;
    double rate = (G->l2 * (kl + kr) + fabs(G->c1[i])) / G->mass[i];
    t = fmin(t, 1.0 / rate);
  }
  return 1e-3 * t;
}

/* Local solution g_loc = -P sqrt(p)/Q (kk: c0/c1) where mu > mu_s, as a
 * starting guess. */
static void local_guess(const grid *G, double *g)
{
  for (int i = 0; i <= G->n; i++)
    g[i] = i < G->nu && G->c1[i] < 0.0 && G->c2[i] > 0.0 ? -G->c1[i] / G->c2[i]
         : i < G->nu && G->c0[i] > 0.0                  ? G->c0[i] / G->c1[i]
                                                        : 0.0;
  if (max_of(g, G->n + 1) == 0.0)
    for (int i = 0; i < G->nu; i++)
      g[i] = 1.0;                        /* nothing flows locally: any positive start */
}

/* Pseudo-transient continuation until the relative residual is below tol or
 * g vanishes. */
static int iterate(const grid *G, double *g, ngf1d_result *res, char *msg, size_t len)
{
  work w;
  if (work_alloc(&w, G->n)) {
    snprintf(msg, len, "out of memory");
    return -1;
  }
  const double tol = 1e-13, g0 = max_of(g, G->n + 1);
  double dtau = first_dtau(G), r_old = INFINITY;
  int rc = -1;
  for (int it = 0; it < 20000; it++) {
    res->iters = it;
    res->residual = residual(G, g, w.F);
    if (max_of(g, G->n + 1) <= 1e-200 * g0) {                      /* decayed to g = 0 */
      for (int i = 0; i <= G->n; i++)
        g[i] = 0.0;
      res->trivial = 1;
      res->residual = 0.0;
      rc = 0;
      break;
    }
    if (res->residual <= tol) {
      rc = 0;
      break;
    }
    if (pseudo_step(G, g, &dtau, &w)) {
      snprintf(msg, len, "pseudo-transient step failed at iteration %d", it);
      break;
    }
    for (int i = 0; i <= G->n; i++)
      g[i] = w.gnew[i];
    double growth = isfinite(r_old) ? r_old / fmax(res->residual, 1e-300) : 1.0;
    dtau *= fmin(10.0, fmax(1.25, growth));                       /* SER, at least x1.25 */
    r_old = res->residual;
  }
  if (rc && !msg[0])
    snprintf(msg, len, "no convergence: residual %.3g after %d iterations", res->residual,
             res->iters);
  work_free(&w);
  return rc;
}

/* The kk equation is linear (c2 = 0) and -J = -dF/dg is symmetric positive
 * definite (c1 >= 0, not all 0, or a Dirichlet end): one Newton step from g
 * solves it exactly, which the pseudo-time iteration only approaches (its
 * stopping test is relative to the flux terms, which grow as 1/h^2). */
static int solve_linear(const grid *G, double *g, ngf1d_result *res, char *msg, size_t len)
{
  work w;
  if (work_alloc(&w, G->n)) {
    snprintf(msg, len, "out of memory");
    return -1;
  }
  int rc = 0;
  residual(G, g, w.F);
  system_matrix(G, g, 0.0, w.diag, w.off);                        /* -J */
  if (!positive_definite(w.diag, w.off, G->nu) || solve_tridiag(&w, G->nu) != GSL_SUCCESS) {
    snprintf(msg, len, "kk equation: the matrix is not positive definite");
    rc = -1;
  } else {
    for (int i = 0; i < G->nu; i++)
      g[i] += w.delta[i];
    res->iters = 1;
    res->residual = residual(G, g, w.F);
  }
  work_free(&w);
  return rc;
}

/* Newton steps on the NGF equation from g until the step is at rounding level
 * (at most maxit); returns the relative residual. The pseudo-time iteration
 * stops at a residual of 1e-13 of the sum of the magnitudes of the terms,
 * which the flux terms dominate (l^2/h^2 against |P|): that leaves g uncertain
 * to ~1e-9 and, started from a neighbouring solution, may not move it at all,
 * while the torque search needs omega(R_i) smooth in tau_i well below its 1e-8
 * tolerance. The stable branch has -J positive definite; where it is not, no
 * step is taken. */
static double polish(const grid *G, double *g, ngf1d_result *res, int maxit)
{
  work w;
  if (work_alloc(&w, G->n))
    return INFINITY;
  for (int it = 0; it < maxit; it++) {
    residual(G, g, w.F);
    system_matrix(G, g, 0.0, w.diag, w.off);                      /* -J */
    if (!positive_definite(w.diag, w.off, G->nu) || solve_tridiag(&w, G->nu) != GSL_SUCCESS)
      break;
    double dmax = 0.0;
    for (int i = 0; i < G->nu; i++) {
      g[i] = fmax(g[i] + w.delta[i], 0.0);
      dmax = fmax(dmax, fabs(w.delta[i]));
    }
    res->iters++;
    if (dmax <= 1e-15 * max_of(g, G->n + 1))
      break;
  }
  res->residual = residual(G, g, w.F);
  work_free(&w);
  return res->residual;
}

/* gdot = g mu and v by the trapezoid rule from the no-slip end (node n). */
static void finish(const grid *G, ngf1d_result *res)
{
  for (int i = 0; i <= G->n; i++) {
    res->pos[i] = G->pos[i];
    res->gdot[i] = res->g[i] * G->mu[i];
  }
  res->v[G->n] = 0.0;
  for (int i = G->n - 1; i >= 0; i--)
    res->v[i] = res->v[i + 1] + 0.5 * (res->gdot[i] * G->vw[i] + res->gdot[i + 1] * G->vw[i + 1]);
}

static int result_alloc(ngf1d_result *res, int n)
{
  size_t m = (size_t)n + 1;
  *res = (ngf1d_result){.n = n};
  res->pos = calloc(m, sizeof(double));
  res->g = calloc(m, sizeof(double));
  res->gdot = calloc(m, sizeof(double));
  res->v = calloc(m, sizeof(double));
  if (!res->pos || !res->g || !res->gdot || !res->v) {
    ngf1d_result_free(res);
    return -1;
  }
  return 0;
}

void ngf1d_result_free(ngf1d_result *res)
{
  free(res->pos);
  free(res->g);
  free(res->gdot);
  free(res->v);
  res->pos = res->g = res->gdot = res->v = NULL;
}

int ngf1d_solve(const ngf1d_problem *pb, const double *guess, ngf1d_result *res, char *msg,
                size_t len)
{
  msg[0] = '\0';
  *res = (ngf1d_result){0};
  if (ngf1d_validate(pb, msg, len))
    return -1;
  grid G;
  if (build(pb, &G) || result_alloc(res, pb->n)) {
    snprintf(msg, len, "out of memory");
    return -1;
  }
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  if (guess)
    for (int i = 0; i <= G.n; i++)
      res->g[i] = i < G.nu && guess[i] > 0.0 ? guess[i] : 0.0;
  else
    local_guess(&G, res->g);
  int rc = 0;
  if (pb->A == 0.0) {                                             /* annulus, local model */
    for (int i = 0; i <= G.n; i++)
      res->g[i] = local_g(pb, G.mu[i]);
    res->trivial = max_of(res->g, G.n + 1) == 0.0;
  } else if (pb->equation == NGF1D_EQ_KK) {
    rc = solve_linear(&G, res->g, res, msg, len);
  } else if (pb->geometry == NGF1D_ANNULUS && guess && max_of(res->g, G.n + 1) > 0.0 &&
             polish(&G, res->g, res, 8) <= 1e-13 && max_of(res->g, G.n + 1) > 0.0) {
    /* the torque search's warm start, a neighbouring solution: Newton's
     * method alone, else (below) the pseudo-time iteration from it */
  } else {
    if (guess && pb->geometry == NGF1D_ANNULUS)                   /* Newton failed: restart */
      for (int i = 0; i <= G.n; i++)
        res->g[i] = i < G.nu && guess[i] > 0.0 ? guess[i] : 0.0;
    res->iters = 0;
    rc = iterate(&G, res->g, res, msg, len);
    if (rc == 0 && !res->trivial && pb->geometry == NGF1D_ANNULUS)
      polish(&G, res->g, res, 4);
  }
  gsl_set_error_handler(old);
  finish(&G, res);
  grid_free(&G);
  return rc;
}

/* ------------------------------------------------------------ references */

double ngf1d_hstop(const ngf1d_problem *pb)
{
  double alpha = -coef_P(pb, tan(pb->theta));                    /* -P(tan theta) */
  if (pb->form == NGF1D_DK && tan(pb->theta) >= pb->mu_2)
    return 0.0;
  if (!(alpha > 0.0))
    return INFINITY;
  return 0.5 * M_PI * pb->A * pb->d / sqrt(alpha);               /* (pi A d/2)/sqrt(alpha) */
}

/* Lowest eigenvalue lam of T phi = lam m phi, T the flux matrix of the chute
 * grid in xi (H-free), m = int xi over the cells, by inverse iteration. */
static double chute_eigenvalue(int n)
{
  ngf1d_problem unit;
  ngf1d_defaults(&unit, NGF1D_CHUTE);
  unit.H = 1.0;
  unit.n = n;
  grid G;
  work w;
  if (build(&unit, &G))
    return NAN;
  if (work_alloc(&w, n)) {
    grid_free(&G);
    return NAN;
  }
  double *x = w.gnew, lam = NAN;
  for (int i = 0; i < n; i++)
    x[i] = 1.0;
  for (int it = 0; it < 200; it++) {
    G.l2 = 1.0;
    system_matrix(&G, x, 0.0, w.diag, w.off);                     /* T + diag(c1 + 2 c2 x) */
    for (int i = 0; i < n; i++)
      w.diag[i] -= G.c1[i] + 2.0 * G.c2[i] * x[i];                 /* T alone */
    for (int i = 0; i < n; i++)
      w.F[i] = G.mass[i] * x[i];                                   /* m x (times 4 H^2 = 4) */
    if (solve_tridiag(&w, n) != GSL_SUCCESS)
      break;
    double num = 0.0, den = 0.0;
    for (int i = 0; i < n; i++) {
      num += w.delta[i] * G.mass[i] * x[i];                        /* y^T M x */
      den += w.delta[i] * G.mass[i] * w.delta[i];                  /* y^T M y */
    }
    double lam_new = num / den, nrm = sqrt(den);
    for (int i = 0; i < n; i++)
      x[i] = w.delta[i] / nrm;
    if (fabs(lam_new - lam) <= 1e-15 * lam_new)
      break;
    lam = lam_new;
  }
  work_free(&w);
  grid_free(&G);
  return lam;                                                      /* of T phi = lam (4 m) phi */
}

double ngf1d_hstop_discrete(const ngf1d_problem *pb)
{
  double alpha = -coef_P(pb, tan(pb->theta));
  if (!(alpha > 0.0))
    return INFINITY;
  /* mass = 4 H^2 m with H = 1: lam = l^2-free rate, threshold alpha = l^2 lam / H^2 */
  return pb->A * pb->d * sqrt(chute_eigenvalue(pb->n) / alpha);
}

static double annulus_local_omega(const ngf1d_problem *pb, double r);

double ngf1d_local_v(const ngf1d_problem *pb, double pos)
{
  double c = 1.0 / (pb->d * sqrt(pb->rho_s));                      /* gdot = I sqrt(p) c */
  if (pb->geometry == NGF1D_ANNULUS)
    return pos * annulus_local_omega(pb, pos);                     /* v_theta = r omega */
  if (pb->geometry == NGF1D_CHUTE) {
    double kap = pb->rho * pb->grav * cos(pb->theta), H = pb->H, s = H - pos;  /* depth */
    double pb0 = pb->p_top + kap * H, pz = pb->p_top + kap * (s > 0.0 ? s : 0.0);
    return local_I(pb, tan(pb->theta)) * c * (2.0 / 3.0) *        /* int sqrt(p) dz */
           (pow(pb0, 1.5) - pow(pz, 1.5)) / kap;
  }
  double k = pb->rho * pb->grav / pb->p, a = fmax(fabs(pos), pb->mu_s / k), e = 0.5 * pb->L;
  if (a >= e)
    return 0.0;
  double dmu = pb->mu_2 - pb->mu_s, C = c * sqrt(pb->p);
  if (pb->form == NGF1D_HS21)                                      /* int (k x - mu_s)/b */
    return C * pb->I0 / dmu * (0.5 * k * (e * e - a * a) - pb->mu_s * (e - a));
  /* int I0 (k x - mu_s)/(mu_2 - k x) dx = I0 [-x - (dmu/k) ln(mu_2 - k x)] */
  return C * pb->I0 * (-(e - a) - dmu / k * log((pb->mu_2 - k * e) / (pb->mu_2 - k * a)));
}

/* ---------------------------------------------------------------- annulus */

/* Local angular velocity omega(r) = int_r^R_o gdot_loc(r') dr'/r' at pb->tau_i,
 * gdot_loc = I_loc(mu) C, C = sqrt(p/rho_s)/d. With mu = m (R_i/r)^2
 * (m = tau_i/p), dr/r = -dmu/(2 mu), shear only for r < R_c = R_i sqrt(m/mu_s),
 * e = min(R_c, R_o), u_a = mu(r), u_e = mu(e):
 *   hs21: gdot = C I0 (mu - mu_s)/dmu,
 *         omega = (C I0/dmu) [(u_a - u_e)/2 - mu_s ln(e/r)];
 *   dk:   gdot = C I0 (mu - mu_s)/(mu_2 - mu), and with
 *         (u - mu_s)/((mu_2 - u) u) = (dmu/(mu_2 - u) - mu_s/u)/mu_2,
 *         omega = (C I0/(2 mu_2)) [dmu ln((mu_2 - u_e)/(mu_2 - u_a)) - 2 mu_s ln(e/r)].
 * Test zones (r_step > 0): gdot constant on each, omega a sum of gdot ln(b/a). */
static double annulus_local_omega(const ngf1d_problem *pb, double r)
{
  const double C = sqrt(pb->p / pb->rho_s) / pb->d, m = pb->tau_i / pb->p;
  const double dmu = pb->mu_2 - pb->mu_s;
  if (pb->r_step > 0.0) {
    double gi = local_I(pb, m) * C, go = local_I(pb, pb->mu_out) * C;   /* gdot per zone */
    if (r >= pb->r_step)
      return go * log(pb->Ro / r);
    return gi * log(pb->r_step / r) + go * log(pb->Ro / pb->r_step);
  }
  if (!(m > pb->mu_s))
    return 0.0;
  double Rc = pb->mu_s > 0.0 ? pb->Ri * sqrt(m / pb->mu_s) : INFINITY, e = fmin(Rc, pb->Ro);
  if (r >= e)
    return 0.0;
  double ua = m * (pb->Ri / r) * (pb->Ri / r), ue = m * (pb->Ri / e) * (pb->Ri / e);
  if (pb->form == NGF1D_HS21)
    return C * pb->I0 / dmu * (0.5 * (ua - ue) - pb->mu_s * log(e / r));
  return C * pb->I0 / (2.0 * pb->mu_2) *
         (dmu * log((pb->mu_2 - ue) / (pb->mu_2 - ua)) - 2.0 * pb->mu_s * log(e / r));
}

/* The unknown of the torque search: s = ln(tau_i/p - mu_s). omega(R_i) grows
 * with tau_i and vanishes for tau_i <= mu_s p (g_loc = 0 and, in the NGF
 * equation, P > 0 everywhere: only g = 0), nearly as a power of tau_i/p - mu_s
 * above, so F(s) = omega(R_i)/Omega - 1 is smooth and monotone in s. */
static double tau_of(const ngf1d_problem *pb, double s)
{
  return (pb->mu_s + exp(s)) * pb->p;
}

typedef double (*root_fn)(double s, void *ctx);

/* Root of the increasing f from s0: bracket by steps of ln 2 (below s_cap,
 * approached geometrically), then Brent (GSL). Stops when |f| <= 1e-12 (far
 * below the 1e-8 the V12 comparison needs, above the rounding of a solve) or
 * when the bracket is 1e-13 wide in s (f changes by about 2 per unit s, so
 * then |f| is at most ~1e-12 plus the rounding). NAN from f aborts. */
static int find_root(root_fn f, void *ctx, double s0, double s_cap, double *s_out)
{
  double lo = s0, hi = s0, f0 = f(s0, ctx), fl, fh;
  if (!isfinite(f0))
    return -1;
  if (f0 == 0.0) {
    *s_out = s0;
    return 0;
  }
  fl = fh = f0;
  for (int k = 0; k < 200 && fh < 0.0; k++) {
    lo = hi;
    fl = fh;
    hi = fmin(hi + M_LN2, 0.5 * (hi + s_cap));                     /* x doubled, or halfway to cap */
    if (!isfinite(fh = f(hi, ctx)))
      return -1;
  }
  for (int k = 0; k < 200 && fl > 0.0; k++) {
    hi = lo;
    fh = fl;
    lo -= M_LN2;                                                   /* x halved */
    if (!isfinite(fl = f(lo, ctx)))
      return -1;
  }
  if (!(fl <= 0.0 && fh >= 0.0))
    return -1;
  if (fl == 0.0 || fh == 0.0) {
    *s_out = fl == 0.0 ? lo : hi;
    return 0;
  }
  gsl_function F = {.function = f, .params = ctx};
  gsl_root_fsolver *rs = gsl_root_fsolver_alloc(gsl_root_fsolver_brent);
  if (!rs || gsl_root_fsolver_set(rs, &F, lo, hi) != GSL_SUCCESS) {
    gsl_root_fsolver_free(rs);
    return -1;
  }
  int rc = -1;
  for (int it = 0; it < 200; it++) {
    if (gsl_root_fsolver_iterate(rs) != GSL_SUCCESS)
      break;
    double s = gsl_root_fsolver_root(rs), fs = f(s, ctx);
    if (!isfinite(fs))
      break;
    *s_out = s;
    if (fabs(fs) <= 1e-12 ||
        gsl_root_fsolver_x_upper(rs) - gsl_root_fsolver_x_lower(rs) <= 1e-13) {
      rc = 0;
      break;
    }
  }
  gsl_root_fsolver_free(rs);
  return rc;
}

typedef struct annulus_ctx {
  ngf1d_problem *pb;
  ngf1d_result res;   /* the solution of the last evaluation */
  double *guess;      /* the last flowing g, warm start of the NGF equation */
  int have_guess, evals;
  char *msg;
  size_t len;
} annulus_ctx;

static double annulus_f(double s, void *vctx)
{
  annulus_ctx *c = vctx;
  c->pb->tau_i = tau_of(c->pb, s);
  ngf1d_result_free(&c->res);
  const double *guess = c->pb->equation == NGF1D_EQ_NGF && c->have_guess ? c->guess : NULL;
  c->evals++;
  if (ngf1d_solve(c->pb, guess, &c->res, c->msg, c->len))
    return NAN;
  if (!c->res.trivial) {
    for (int i = 0; i <= c->res.n; i++)
      c->guess[i] = c->res.g[i];
    c->have_guess = 1;
  }
  return c->res.v[0] / c->pb->Omega - 1.0;                         /* omega(R_i)/Omega - 1 */
}

static double local_f(double s, void *vctx)
{
  ngf1d_problem *pb = vctx;
  pb->tau_i = tau_of(pb, s);
  return annulus_local_omega(pb, pb->Ri) / pb->Omega - 1.0;
}

/* ln(tau_i/p - mu_s) is bounded by ln(mu_2 - mu_s) for the dk law. */
static double s_cap(const ngf1d_problem *pb)
{
  return pb->form == NGF1D_DK ? log(pb->mu_2 - pb->mu_s) : INFINITY;
}

double ngf1d_annulus_local_tau(const ngf1d_problem *pb)
{
  ngf1d_problem q = *pb;
  char msg[128];
  q.tau_i = 0.0;
  if (q.geometry != NGF1D_ANNULUS || q.r_step > 0.0 || !(q.Omega > 0.0) ||
      ngf1d_validate(&q, msg, sizeof msg))
    return NAN;
  /* start from the thin-band limit: omega_i ~ (C/b) x^2 / (4 mu_s), x = mu_i - mu_s */
  double C = sqrt(q.p / q.rho_s) / q.d, b = (q.mu_2 - q.mu_s) / q.I0;
  double x0 = sqrt(4.0 * fmax(q.mu_s, 1e-3) * b * q.Omega / C), s;
  double s0 = fmin(log(x0), 0.5 * (log(x0) + s_cap(&q)));
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  int rc = find_root(local_f, &q, s0, s_cap(&q), &s);
  gsl_set_error_handler(old);
  return rc ? NAN : tau_of(&q, s);
}

int ngf1d_annulus_solve(ngf1d_problem *pb, ngf1d_result *res, int *evals, double *omega_err,
                        char *msg, size_t len)
{
  msg[0] = '\0';
  *res = (ngf1d_result){0};
  *evals = 0;
  *omega_err = NAN;
  pb->tau_i = 0.0;
  if (pb->geometry != NGF1D_ANNULUS || !(pb->Omega > 0.0) || pb->r_step > 0.0) {
    snprintf(msg, len, "the torque search needs the annulus, Omega > 0 and no test zones");
    return -1;
  }
  if (ngf1d_validate(pb, msg, len))
    return -1;
  double tl = ngf1d_annulus_local_tau(pb);
  if (!isfinite(tl)) {
    snprintf(msg, len, "no local solution for Omega = %g", pb->Omega);
    return -1;
  }
  annulus_ctx c = {.pb = pb, .msg = msg, .len = len};
  c.guess = calloc((size_t)pb->n + 1, sizeof(double));
  if (!c.guess) {
    snprintf(msg, len, "out of memory");
    return -1;
  }
  double s = NAN;
  gsl_error_handler_t *old = gsl_set_error_handler_off();
  int rc = find_root(annulus_f, &c, log(tl / pb->p - pb->mu_s), s_cap(pb), &s);
  gsl_set_error_handler(old);
  if (rc == 0 && tau_of(pb, s) != pb->tau_i)                     /* last solve elsewhere */
    rc = isfinite(annulus_f(s, &c)) ? 0 : -1;
  *evals = c.evals;
  free(c.guess);
  if (rc) {
    if (!msg[0])
      snprintf(msg, len, "torque search failed after %d solves", c.evals);
    ngf1d_result_free(&c.res);
    return -1;
  }
  *res = c.res;
  *omega_err = res->v[0] / pb->Omega - 1.0;
  return 0;
}

/* int_r1^r2 sqrt(P(mu(r))) dr (P > 0 beyond R_c) by 4-point Gauss-Legendre on
 * 64 equal pieces: the integrand is smooth there, the rule exact to rounding.
 * (For hs21 it is q - sqrt(c) atan(q/sqrt(c)), q = sqrt(mu_s r^2 - c),
 * c = mu_i R_i^2, between the ends.) */
static double tail_integral(const ngf1d_problem *pb, double r1, double r2)
{
  const int m = 64;
  const double h = (r2 - r1) / m;
  double sum = 0.0;
  for (int k = 0; k < m; k++)
    for (int q = 0; q < 4; q++) {
      double r = r1 + h * (k + 0.5 + 0.5 * gauss4_x[q]);
      sum += 0.5 * h * gauss4_w[q] * sqrt(fmax(coef_P(pb, ngf1d_mu(pb, r)), 0.0));
    }
  return sum;
}

void ngf1d_annulus_tail(const ngf1d_problem *pb, const ngf1d_result *res, ngf1d_tail *t)
{
  const double mu_i = pb->tau_i / pb->p;
  *t = (ngf1d_tail){.Rc = mu_i > pb->mu_s ? pb->Ri * sqrt(mu_i / pb->mu_s) : pb->Ri,
                    .r1 = NAN, .r2 = NAN, .fit = NAN, .xi = NAN, .wkb = NAN};
  if (pb->r_step > 0.0 || !(t->Rc < pb->Ro))
    return;
  t->r1 = t->Rc + 0.25 * (pb->Ro - t->Rc);
  t->r2 = t->Rc + 0.75 * (pb->Ro - t->Rc);
  double rm = 0.5 * (t->r1 + t->r2), l = pb->A * pb->d;
  t->xi = l / sqrt(coef_P(pb, ngf1d_mu(pb, rm)));                 /* l / sqrt(|P|) */
  t->wkb = (t->r2 - t->r1) * l / tail_integral(pb, t->r1, t->r2);
  double sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
  int m = 0;
  for (int i = 0; i <= res->n; i++) {
    double r = res->pos[i], vt = r * res->v[i], x = r - rm;
    if (r < t->r1 || r > t->r2)
      continue;
    if (!(vt > 0.0))
      return;                                                      /* nothing moves there */
    double y = log(vt);
    sx += x;
    sy += y;
    sxx += x * x;
    sxy += x * y;
    m++;
  }
  if (m < 3)
    return;
  double slope = (m * sxy - sx * sy) / (m * sxx - sx * sx);        /* least squares */
  t->fit = -1.0 / slope;
}
