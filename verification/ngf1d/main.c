/* main.c: command line of the steady 1D NGF reference solver (ngf1d.h).
 *
 *   ngf1d chute  [options]   inclined chute, prints z,g,gdot,v from the base up
 *   ngf1d vchute [options]   vertical chute, prints x,g,gdot,v across the width
 *   ngf1d annulus [options]  annular shear: finds the torque for Omega, prints
 *                            r,g,gdot,mu,omega,v_theta,v_theta_local
 *   ngf1d hstop  [options]   prints Hstop (eq. 3.1) and the discrete threshold
 * Comment lines (#) give the parameters, Hstop and the solver statistics.
 * Exit status 0, 1 on a solver failure, 2 on a usage error. */
#define _DEFAULT_SOURCE /* M_PI, getopt_long */
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ngf1d.h"

static void usage(FILE *f)
{
  fputs("usage: ngf1d chute|vchute|annulus|hstop [options]\n"
        "  --n N           grid intervals (400)\n"
        "  --form F        dk ([DK-silo], default) or hs21 (linearised [HS21])\n"
        "  --equation E    ngf (steady NGF, default) or kk (vchute, annulus: the linear steady\n"
        "                  form l^2 g'' = |P| (g - g_loc) of [D-thesis] eq. 2.29-2.30)\n"
        "  --b B           sets I0 = (mu_2 - mu_s) / B (b of the linear law mu_s + b I)\n"
        "  --local         print the local (A = 0) velocity x,v in closed form instead\n"
        "  --A --d --mu_s --mu_2 --I0 --rho_s   material (m, kg/m^3)\n"
        "  --rho --grav    bulk density [kg/m^3] (1500), gravity [m/s^2] (9.81)\n"
        "chute:  --theta DEG (27)  --H M | --H-rel R (H = R Hstop; default 3)\n"
        "        --p-top PA  surcharge on the surface (0: free surface)\n"
        "        defaults: [DK-silo] Fig. 2: A 0.25, d 5 mm, mu_s 0.3819, mu_2 1.5, I0 0.279\n"
        "vchute: --L M (1)  --p PA (900)  --wall dirichlet|neumann (dirichlet)\n"
        "        defaults: [D-thesis] Table 4.1: A 0.48, d 0.05 m, mu_2 0.6435, form hs21\n"
        "annulus: --Ri M (0.06)  --Ro M (0.08)  --Omega RAD/S (0.01)  --P PA (100, = --p)\n"
        "        --tau-i PA  solve at this inner wall stress instead of finding it from Omega\n"
        "        A = 0 allowed (the local model); g' = 0 at both walls\n"
        "        defaults: Henann and Kamrin 2013: A 0.48, d 1 mm, mu_s 0.3819, form hs21 with\n"
        "        b = 0.9377 (mu_2 0.6435, I0 0.279), rho_s 2450, equation kk\n", f);
}

static int parse_double(const char *s, double *out)
{
  char *end;
  double v = strtod(s, &end);
  if (end == s || *end != '\0' || !isfinite(v))
    return -1;
  *out = v;
  return 0;
}

enum { O_N = 1, O_FORM, O_A, O_D, O_MUS, O_MU2, O_I0, O_RHOS, O_RHO, O_GRAV, O_THETA, O_H,
       O_HREL, O_L, O_P, O_WALL, O_PTOP, O_EQ, O_B, O_LOCAL, O_RI, O_RO, O_OMEGA, O_TAUI,
       O_HELP };

static const struct option options[] = {
  {"n", required_argument, NULL, O_N},       {"form", required_argument, NULL, O_FORM},
  {"A", required_argument, NULL, O_A},       {"d", required_argument, NULL, O_D},
  {"mu_s", required_argument, NULL, O_MUS},  {"mu_2", required_argument, NULL, O_MU2},
  {"I0", required_argument, NULL, O_I0},     {"rho_s", required_argument, NULL, O_RHOS},
  {"rho", required_argument, NULL, O_RHO},   {"grav", required_argument, NULL, O_GRAV},
  {"theta", required_argument, NULL, O_THETA}, {"H", required_argument, NULL, O_H},
  {"H-rel", required_argument, NULL, O_HREL}, {"L", required_argument, NULL, O_L},
  {"p", required_argument, NULL, O_P},       {"wall", required_argument, NULL, O_WALL},
  {"p-top", required_argument, NULL, O_PTOP}, {"equation", required_argument, NULL, O_EQ},
  {"b", required_argument, NULL, O_B},      {"local", no_argument, NULL, O_LOCAL},
  {"Ri", required_argument, NULL, O_RI},     {"Ro", required_argument, NULL, O_RO},
  {"Omega", required_argument, NULL, O_OMEGA}, {"P", required_argument, NULL, O_P},
  {"tau-i", required_argument, NULL, O_TAUI},
  {"help", no_argument, NULL, O_HELP},       {NULL, 0, NULL, 0}};

/* Option c with argument s into pb; *hrel collects --H-rel, *b --b. 0 or -1. */
static int apply(ngf1d_problem *pb, int c, const char *s, double *hrel, double *b)
{
  double v;
  if (c == O_EQ) {
    if (strcmp(s, "ngf") && strcmp(s, "kk"))
      return -1;
    pb->equation = strcmp(s, "kk") ? NGF1D_EQ_NGF : NGF1D_EQ_KK;
    return 0;
  }
  if (c == O_FORM) {
    if (strcmp(s, "dk") && strcmp(s, "hs21"))
      return -1;
    pb->form = strcmp(s, "dk") ? NGF1D_HS21 : NGF1D_DK;
    return 0;
  }
  if (c == O_WALL) {
    if (strcmp(s, "dirichlet") && strcmp(s, "neumann"))
      return -1;
    pb->wall_neumann = strcmp(s, "neumann") == 0;
    return 0;
  }
  if (parse_double(s, &v))
    return -1;
  double *const fields[] = {[O_A] = &pb->A, [O_D] = &pb->d, [O_MUS] = &pb->mu_s,
                            [O_MU2] = &pb->mu_2, [O_I0] = &pb->I0, [O_RHOS] = &pb->rho_s,
                            [O_RHO] = &pb->rho, [O_GRAV] = &pb->grav, [O_H] = &pb->H,
                            [O_L] = &pb->L, [O_P] = &pb->p, [O_HREL] = hrel,
                            [O_PTOP] = &pb->p_top, [O_B] = b, [O_RI] = &pb->Ri,
                            [O_RO] = &pb->Ro, [O_OMEGA] = &pb->Omega, [O_TAUI] = &pb->tau_i};
  if (c == O_N) {
    if (v != floor(v) || v < 4 || v > 1e8)
      return -1;
    pb->n = (int)v;
  } else if (c == O_THETA) {
    pb->theta = v * M_PI / 180.0;
  } else if (c < (int)(sizeof fields / sizeof fields[0]) && fields[c]) {
    *fields[c] = v;
  } else {
    return -1;
  }
  return 0;
}

static const char *geometry_name(int geometry)
{
  return geometry == NGF1D_CHUTE ? "chute" : geometry == NGF1D_VCHUTE ? "vchute" : "annulus";
}

static void print_header(const ngf1d_problem *pb)
{
  printf("# ngf1d %s, form %s, equation %s: A %g d %g mu_s %g mu_2 %g I0 %g rho_s %g rho %g grav %g n %d\n",
         geometry_name(pb->geometry), pb->form == NGF1D_DK ? "dk" : "hs21",
         pb->equation == NGF1D_EQ_KK ? "kk" : "ngf", pb->A, pb->d, pb->mu_s, pb->mu_2, pb->I0, pb->rho_s, pb->rho, pb->grav, pb->n);
  if (pb->geometry == NGF1D_CHUTE)
    printf("# theta %g deg, H %.9g m, Hstop %.9g m (eq. 3.1), H/Hstop %.6g, p_top %g Pa\n",
           pb->theta * 180.0 / M_PI, pb->H, ngf1d_hstop(pb), pb->H / ngf1d_hstop(pb), pb->p_top);
  else if (pb->geometry == NGF1D_VCHUTE)
    printf("# L %g m, p %g Pa, wall stress ratio %.6g, walls %s\n", pb->L, pb->p,
           pb->rho * pb->grav * 0.5 * pb->L / pb->p, pb->wall_neumann ? "g' = 0" : "g = 0");
  else
    printf("# R_i %g m, R_o %g m, Omega %g rad/s, p %g Pa, b %.6g, g' = 0 at both walls\n",
           pb->Ri, pb->Ro, pb->Omega, pb->p, (pb->mu_2 - pb->mu_s) / pb->I0);
}

/* Annulus: summary lines and r,g,gdot,mu,omega,v_theta,v_theta_local from R_i
 * out; loc has the tau_i of the local solution at the same Omega. */
static void print_annulus(const ngf1d_problem *pb, const ngf1d_problem *loc,
                          const ngf1d_result *r, int evals, double omega_err)
{
  ngf1d_tail t;
  ngf1d_annulus_tail(pb, r, &t);
  double Rc_loc = pb->Ri * sqrt(loc->tau_i / (pb->p * pb->mu_s));
  printf("# iterations %d, relative residual %.3g%s\n", r->iters, r->residual,
         r->trivial ? ", trivial solution g = 0 (no flow)" : "");
  if (evals > 0)
    printf("# torque search: %d solves, omega(R_i)/Omega - 1 = %.3g\n", evals, omega_err);
  printf("# tau_i %.12g Pa, mu_i %.9g, torque per unit length T = 2 pi R_i^2 tau_i %.12g N m/m, "
         "band edge R_c %.12g m (R_c - R_i = %.6g d)\n", pb->tau_i, pb->tau_i / pb->p,
         2.0 * M_PI * pb->Ri * pb->Ri * pb->tau_i, t.Rc, (t.Rc - pb->Ri) / pb->d);
  printf("# local (A = 0) closed form: tau_i %.12g Pa, T %.12g N m/m, R_c %.12g m "
         "(R_c - R_i = %.6g d)\n", loc->tau_i, 2.0 * M_PI * pb->Ri * pb->Ri * loc->tau_i, Rc_loc,
         (Rc_loc - pb->Ri) / pb->d);
  printf("# creep tail, r in [%.6g, %.6g] m: decay length fitted to ln v_theta %.6g m, "
         "A d / sqrt(|P(mu)|) at the centre %.6g m, WKB mean %.6g m\n", t.r1, t.r2, t.fit,
         t.xi, t.wkb);
  printf("r,g,gdot,mu,omega,v_theta,v_theta_local\n");
  for (int i = 0; i <= r->n; i++) {
    double x = r->pos[i];
    printf("%.12g,%.12g,%.12g,%.12g,%.12g,%.12g,%.12g\n", x, r->g[i], r->gdot[i],
           ngf1d_mu(pb, x), r->v[i], x * r->v[i], ngf1d_local_v(loc, x));
  }
}

/* Profile: chute from the base up (node n to 0); vchute from -L/2 to L/2. */
static void print_profile(const ngf1d_problem *pb, const ngf1d_result *r)
{
  printf("# iterations %d, relative residual %.3g%s\n", r->iters, r->residual,
         r->trivial ? ", trivial solution g = 0 (no flow)" : "");
  if (pb->geometry == NGF1D_CHUTE) {
    printf("z,g,gdot,v\n");
    for (int i = r->n; i >= 0; i--)
      printf("%.12g,%.12g,%.12g,%.12g\n", r->pos[i], r->g[i], r->gdot[i], r->v[i]);
    return;
  }
  printf("x,g,gdot,v\n");
  for (int i = r->n; i > 0; i--)
    printf("%.12g,%.12g,%.12g,%.12g\n", -r->pos[i], r->g[i], r->gdot[i], r->v[i]);
  for (int i = 0; i <= r->n; i++)
    printf("%.12g,%.12g,%.12g,%.12g\n", r->pos[i], r->g[i], r->gdot[i], r->v[i]);
}

/* Annulus: the torque search (or the given tau_i), the local closed form at
 * the same Omega, the profile. Exit status as main's. */
static int run_annulus(ngf1d_problem *pb, int local)
{
  char msg[256];
  ngf1d_problem loc = *pb;
  const int given = pb->tau_i > 0.0;
  loc.tau_i = 0.0;
  if (ngf1d_validate(pb, msg, sizeof msg)) {
    fprintf(stderr, "ngf1d: %s\n", msg);
    return 1;
  }
  loc.tau_i = given ? pb->tau_i : ngf1d_annulus_local_tau(pb);    /* local solution */
  if (!isfinite(loc.tau_i)) {
    fprintf(stderr, "ngf1d: no local solution for Omega = %g\n", pb->Omega);
    return 1;
  }
  if (local) {                  /* closed-form local profile on the grid of the solver */
    print_header(pb);
    printf("# local (A = 0) profile in closed form, tau_i %.12g Pa\nr,v_theta\n", loc.tau_i);
    for (int i = 0; i <= pb->n; i++) {
      double x = i == pb->n ? pb->Ro : pb->Ri + (pb->Ro - pb->Ri) * i / pb->n;
      printf("%.12g,%.12g\n", x, ngf1d_local_v(&loc, x));
    }
    return 0;
  }
  ngf1d_result r;
  int evals = 0, rc;
  double err = NAN;
  if (given) {                  /* the torque is given: Omega is the outcome */
    rc = ngf1d_solve(pb, NULL, &r, msg, sizeof msg);
    pb->Omega = rc ? pb->Omega : r.v[0];
  } else {
    rc = ngf1d_annulus_solve(pb, &r, &evals, &err, msg, sizeof msg);
  }
  if (rc)
    fprintf(stderr, "ngf1d: %s\n", msg);
  else {
    print_header(pb);
    print_annulus(pb, &loc, &r, evals, err);
  }
  ngf1d_result_free(&r);
  return rc ? 1 : 0;
}

int main(int argc, char **argv)
{
  if (argc < 2 || (strcmp(argv[1], "chute") && strcmp(argv[1], "vchute") &&
                   strcmp(argv[1], "annulus") && strcmp(argv[1], "hstop"))) {
    usage(stderr);
    return 2;
  }
  int geom = !strcmp(argv[1], "vchute")    ? NGF1D_VCHUTE
           : !strcmp(argv[1], "annulus") ? NGF1D_ANNULUS
                                         : NGF1D_CHUTE;
  ngf1d_problem pb;
  ngf1d_defaults(&pb, geom);
  double hrel = 0.0, b = 0.0;
  int local = 0;
  int c;
  while ((c = getopt_long(argc - 1, argv + 1, "", options, NULL)) != -1) {
    if (c == O_HELP) {
      usage(stdout);
      return 0;
    }
    if (c == O_LOCAL) {
      local = 1;
      continue;
    }
    if (c == '?' || apply(&pb, c, optarg, &hrel, &b)) {
      fprintf(stderr, "ngf1d: bad option or value%s%s\n", c == '?' ? "" : ": ",
              c == '?' ? "" : optarg);
      return 2;
    }
  }
  if (optind < argc - 1) {
    fprintf(stderr, "ngf1d: unexpected argument '%s'\n", argv[optind + 1]);
    return 2;
  }
  if (b != 0.0) {
    if (!(b > 0.0)) {
      fprintf(stderr, "ngf1d: --b must be > 0\n");
      return 2;
    }
    pb.I0 = (pb.mu_2 - pb.mu_s) / b;                      /* b = (mu_2 - mu_s) / I0 */
  }
  if (geom == NGF1D_CHUTE && hrel > 0.0)
    pb.H = hrel * ngf1d_hstop(&pb);
  if (strcmp(argv[1], "hstop") == 0) {
    printf("Hstop %.12g m, discrete (n = %d) %.12g m, Hstop/d %.9g\n", ngf1d_hstop(&pb), pb.n,
           ngf1d_hstop_discrete(&pb), ngf1d_hstop(&pb) / pb.d);
    return 0;
  }
  char msg[256];
  if (geom == NGF1D_ANNULUS)
    return run_annulus(&pb, local);
  if (local) {                  /* closed-form local profile on the grid of the solver */
    if (ngf1d_validate(&pb, msg, sizeof msg)) {
      fprintf(stderr, "ngf1d: %s\n", msg);
      return 1;
    }
    print_header(&pb);
    printf("# local (A = 0) profile in closed form\n%s,v\n", geom == NGF1D_CHUTE ? "z" : "x");
    double lo = geom == NGF1D_CHUTE ? 0.0 : -0.5 * pb.L, span = geom == NGF1D_CHUTE ? pb.H : pb.L;
    for (int i = 0; i <= pb.n; i++) {
      double x = lo + span * i / pb.n;
      printf("%.12g,%.12g\n", x, ngf1d_local_v(&pb, x));
    }
    return 0;
  }
  ngf1d_result r;
  int rc = ngf1d_solve(&pb, NULL, &r, msg, sizeof msg);
  if (rc)
    fprintf(stderr, "ngf1d: %s\n", msg);
  else {
    print_header(&pb);
    print_profile(&pb, &r);
  }
  ngf1d_result_free(&r);
  return rc ? 1 : 0;
}
