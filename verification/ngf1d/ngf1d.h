/* ngf1d.h: an independent steady 1D solver of the nonlocal granular fluidity
 * equation, the reference for the NGF verification cases (MODEL.md sections 5
 * and 8). It shares no code with libgranmpm.
 *
 * Steady form of the MODEL.md section 5 PDE (dg/dt = 0), with l = A d:
 *   l^2 g'' = P(mu) g + Q(mu) g^2 / sqrt(p),   Q = b sqrt(rho_s) d mu,
 *   P = Delta_mu (mu_s - mu)/(mu_2 - mu)  ("dk", [DK-silo] eq. 2.1), or
 *   P = mu_s - mu                         ("hs21", [HS21] eq. 6, linearised),
 * flow rule gdot = g mu.
 * Or (--equation kk, vchute and annulus) the steady form [D-thesis] solves, Kamrin
 * and Koval's linear equation ([D-thesis] eq. 2.28-2.30, MODEL.md section 6):
 *   l^2 g'' = |P(mu)| (g - g_loc),   g_loc = I_loc(mu) sqrt(p/(rho_s d^2)) / mu,
 * I_loc the local law of the form (mu >= mu_s; 0 below). With the hs21 form
 * this is the thesis' xi = A d / sqrt(|mu - mu_s|) and
 * g_loc = sqrt(p/(rho_s d^2)) (mu - mu_s)/(b mu): the linearisation of the
 * steady NGF equation about g_loc, with the same local limit.
 * Geometries:
 *   chute:  inclined layer of depth H at tilt theta; mu = tan(theta),
 *           p = p_top + rho grav cos(theta) (H - z) (p_top = 0: free surface);
 *           g(0) = 0 at the base, g'(H) = 0 at the top; v(z) = int_0^z gdot.
 *   vchute: vertical chute between rough walls at x = -L/2, L/2; uniform p,
 *           mu = rho grav |x| / p (the wall shear carries the weight); g = 0 at
 *           the walls (or g' = 0), symmetric about x = 0; v(+-L/2) = 0,
 *           v the downward speed.
 *   annulus: plane-strain annular (Taylor-Couette) shear without gravity
 *           between a rough inner cylinder r = R_i turning at Omega and a rough
 *           fixed outer one r = R_o (MODEL.md section 8): uniform p, torque
 *           balance tau = tau_i (R_i/r)^2, mu = tau/p; the Laplacian is the
 *           radial one, l^2 (g'' + g'/r) = (local part); g' = 0 at both walls;
 *           gdot = g mu = -r domega/dr, omega(R_o) = 0; tau_i is the one that
 *           gives omega(R_i) = Omega (ngf1d_annulus_solve). A = 0 is allowed
 *           here: the local model, g = g_loc. */
#ifndef NGF1D_H
#define NGF1D_H

#include <stddef.h>

enum ngf1d_form { NGF1D_DK = 0, NGF1D_HS21 };
enum ngf1d_equation { NGF1D_EQ_NGF = 0, NGF1D_EQ_KK };
enum ngf1d_geometry { NGF1D_CHUTE = 0, NGF1D_VCHUTE, NGF1D_ANNULUS };

typedef struct ngf1d_problem {
  int geometry, form;
  int equation;                        /* enum ngf1d_equation */
  double A, d, mu_s, mu_2, I0, rho_s;  /* material: -, m, -, -, -, kg/m^3 */
  double rho, grav;                    /* bulk density [kg/m^3], gravity [m/s^2] */
  double theta, H;                     /* chute: tilt [rad], depth [m] */
  double p_top;                        /* chute: surcharge on the surface [Pa] (0) */
  double L, p;                         /* vchute: width [m]; vchute, annulus: pressure [Pa] */
  int wall_neumann;                    /* vchute walls: 0 g = 0, 1 g' = 0 */
  double Ri, Ro, Omega;                /* annulus: radii [m], inner angular velocity [rad/s] */
  double tau_i;                        /* annulus: shear stress at r = R_i [Pa] (ngf1d_solve
                                          takes it, ngf1d_annulus_solve finds it) */
  double r_step, mu_out;               /* annulus, tests only: r_step > 0 replaces
                                          tau/p by mu_i = tau_i/p for r < r_step and
                                          mu_out beyond (a two-zone problem with a closed
                                          form in Bessel functions I0, K0) */
  int n;                               /* grid intervals */
} ngf1d_problem;

/* Solution on the nodes i = 0..n of the computational grid:
 *   chute:  xi_i = i/n, depth below the surface s = H xi^2 (nodes cluster at
 *           the surface, where g'' ~ s^-1/2), z = H - s: i = 0 is the free
 *           surface, i = n the base;
 *   vchute: x_i = (L/2) i/n, i = 0 the centre, i = n the wall;
 *   annulus: r_i = R_i + (R_o - R_i) i/n, i = 0 the inner (moving) wall, i = n
 *           the outer (fixed) one. */
typedef struct ngf1d_result {
  int n;
  double *pos;       /* z (chute), x (vchute) or r (annulus) [m] */
  double *g, *gdot;  /* fluidity, shear rate [1/s] */
  double *v;         /* velocity [m/s]; annulus: angular velocity omega [rad/s] */
  int iters;         /* pseudo-transient Newton iterations */
  double residual;   /* final residual relative to the size of its terms */
  int trivial;       /* 1 when the solution found is g = 0 */
} ngf1d_result;

/* [DK-silo] Fig. 2(b-c) values (chute), [D-thesis] Table 4.1 (vchute), or
 * (annulus) the annular shear of Henann and Kamrin 2013: R_i = 0.06 m,
 * R_o = 0.08 m, d = 1 mm, A = 0.48, mu_s = 0.3819, b = 0.9377 (mu_2 = 0.6435,
 * I0 = 0.279, the vchute's), rho_s = 2450 kg/m^3, p = 100 Pa, form hs21,
 * the kk equation, Omega = 0.01 rad/s. */
void ngf1d_defaults(ngf1d_problem *pb, int geometry);

/* 0 if the problem is well posed, else -1 with a message. */
int ngf1d_validate(const ngf1d_problem *pb, char *msg, size_t len);

/* Steady solution by pseudo-transient continuation (implicit Euler in a
 * pseudo time with growing steps, each step one Newton linearisation) from
 * guess[0..n] (NULL: the local solution), which ends in Newton's method on
 * the stable branch. Returns 0, or -1 with a message. */
int ngf1d_solve(const ngf1d_problem *pb, const double *guess, ngf1d_result *res, char *msg,
                size_t len);
void ngf1d_result_free(ngf1d_result *res);

/* Chute threshold Hstop: (pi A d/2) / sqrt(-P(tan theta)), i.e. [DK-silo]
 * eq. 3.1 for "dk"; 0 when tan theta >= mu_2 ("dk"), infinity when
 * tan theta <= mu_s. */
double ngf1d_hstop(const ngf1d_problem *pb);

/* The same threshold of the discrete linear operator on pb->n intervals (its
 * lowest eigenvalue in place of (pi/2H)^2). */
double ngf1d_hstop_discrete(const ngf1d_problem *pb);

/* Local (A = 0) velocities: chute v(z) (Bagnold, [DK15] eq. 4.6 for "dk"),
 * vchute v(x) (plug for |x| < mu_s p/(rho grav)), annulus v_theta(r) = r omega
 * at the given tau_i (0 beyond the band edge R_c = R_i sqrt(tau_i/(mu_s p))),
 * all in closed form. */
double ngf1d_local_v(const ngf1d_problem *pb, double pos);

/* Stress ratio mu at pos (z, x or r). */
double ngf1d_mu(const ngf1d_problem *pb, double pos);

/* Annulus: the tau_i for which omega(R_i) = pb->Omega, found by Brent's method
 * on ln(tau_i/p - mu_s) (each evaluation one solve on pb->n intervals); stores
 * it in pb->tau_i and the solution in res. *evals counts the solves,
 * *omega_err is omega(R_i)/Omega - 1 of the solution returned. 0 or -1. */
int ngf1d_annulus_solve(ngf1d_problem *pb, ngf1d_result *res, int *evals, double *omega_err,
                        char *msg, size_t len);

/* Annulus: tau_i of the local (A = 0) closed form for pb->Omega, or NAN. */
double ngf1d_annulus_local_tau(const ngf1d_problem *pb);

/* Annulus: the creep tail beyond the band edge R_c. Over the window
 * r1 = R_c + (R_o - R_c)/4 .. r2 = R_c + 3 (R_o - R_c)/4:
 *   fit:  -1 / (slope of the least-squares line of ln v_theta against r);
 *   xi:   A d / sqrt(|P(mu)|) at the window's centre (A d / sqrt(mu_s - mu)
 *         for hs21; dk: Delta_mu (mu_s - mu)/(mu_2 - mu) under the root);
 *   wkb:  (r2 - r1) / int_r1^r2 dr/xi, the decay length of exp(-int dr/xi)
 *         (slowly varying xi) averaged over the window.
 * All NAN when R_c >= R_o or v_theta vanishes in the window (A = 0). */
typedef struct ngf1d_tail {
  double Rc, r1, r2, fit, xi, wkb;
} ngf1d_tail;
void ngf1d_annulus_tail(const ngf1d_problem *pb, const ngf1d_result *res, ngf1d_tail *t);

#endif
