/* kernels.c: the granmpm NGF kernels (src/nonlocal, src/material/ngf.c)
 * against the independent 1D reference (ngf1d.h), without the MPM solver.
 *
 * Fixed-stress columns: one dense point at the centre of every unit with a
 * prescribed pressure p and stress ratio mu. One iteration is exactly the
 * per-step NGF sequence of MODEL.md section 5:
 *   g_e = sum m g / sum m, lap_e with the ghost rules, g* = max(0, g + k A^2 d^2 lap_e),
 *   x = mpm_material_ngf_fluidity(dt, p, tau_tr, g*, mu g), tau_tr = mu (p + G dt g),
 * the trial stress chosen so that the returned stress ratio mu(x) = tau_tr/(G dt x + p)
 * equals mu when x = g. At the fixed point the split update reads
 *   A^2 d^2 lap_e = P(mu) g + b sqrt(rho_s d^2/p) mu g^2,
 * the steady equation on the unit centres, so the kernels must converge to the
 * ngf1d solution at second order in the unit size, with:
 *   chute:  the base a no-slip wall (Dirichlet ghost), the top free (Neumann),
 *           periodic along the slope, mu = tan(theta), p = p_top + rho grav cos(theta) (H - z);
 *   vchute: no-slip walls left and right, periodic along the flow,
 *           mu = rho grav |x| / p.
 * The p^-1/2 of the g^2 term is the unit mean of the linear reconstruction of
 * the unit pressures (material.p_sample = "unit", mpm_nonlocal_pressure) or
 * the point's own ("point", [DK-silo]). With p_top = 0 (a free surface,
 * p -> 0) the point value samples p^-1/2 at the top unit's centre instead of
 * integrating it over the unit; that costs O(dy^1/2) (the top unit's flux
 * balance is off by O(dy^1/2)), which the last check measures; the unit mean
 * integrates it and keeps second order.
 * Prints "name measured range PASS|FAIL"; exit status = number of failures. */
#define _DEFAULT_SOURCE /* M_PI */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/config.h"
#include "material/material.h"
#include "mesh/mesh.h"
#include "ngf1d.h"
#include "nonlocal/nonlocal.h"

typedef struct tally { int fails, quick; } tally;

static void report(tally *t, const char *name, double measured, double lo, double hi)
{
  int ok = measured >= lo && measured <= hi;
  printf("%-62s %11.5g  in [%g, %g]  %s\n", name, measured, lo, hi, ok ? "PASS" : "FAIL");
  t->fails += !ok;
}

/* granmpm parameters matching a reference problem, with the given
 * enum mpm_material_ngf_p_sample. */
static mpm_material_params params_of(const ngf1d_problem *pb, int sample)
{
  mpm_material_params par = {.E = 1e7, .nu = 0.3, .rho_s = pb->rho_s, .rho_c = pb->rho,
                             .mu_s = pb->mu_s, .mu_2 = pb->mu_2, .I0 = pb->I0, .d = pb->d,
                             .A = pb->A, .t0 = 1e-3,
                             .form = pb->form == NGF1D_DK ? MPM_NGF_DK : MPM_NGF_HS21,
                             .p_sample = sample};
  mpm_material_params_derive(&par);
  return par;
}

/* A column of points (one per unit) on mesh m with the given edges. */
typedef struct column {
  mpm_mesh m;
  int edge[4];
  size_t n;
  double *x, *y, *mass, *g, *p, *mu;
} column;

static void column_free(column *c)
{
  free(c->x);
  free(c->y);
  free(c->mass);
  free(c->g);
  free(c->p);
  free(c->mu);
}

static int column_alloc(column *c)
{
  mpm_err err = {0};
  if (mpm_mesh_setup(&c->m, &err) != MPM_OK)
    return -1;
  c->n = (size_t)c->m.nx * (size_t)c->m.ny;
  c->x = malloc(c->n * sizeof(double));
  c->y = malloc(c->n * sizeof(double));
  c->mass = malloc(c->n * sizeof(double));
  c->g = malloc(c->n * sizeof(double));
  c->p = malloc(c->n * sizeof(double));
  c->mu = malloc(c->n * sizeof(double));
  if (!c->x || !c->y || !c->mass || !c->g || !c->p || !c->mu)
    return -1;
  for (int j = 0, k = 0; j < c->m.ny; j++)
    for (int i = 0; i < c->m.nx; i++, k++) {
      c->x[k] = c->m.x0 + (i + 0.5) * c->m.dx;                   /* unit centres */
      c->y[k] = c->m.y0 + (j + 0.5) * c->m.dy;
      c->mass[k] = 1.0;
      c->g[k] = 1.0;                                             /* positive start */
    }
  return 0;
}

/* Fixed-stress iteration to steady state (relative change < 1e-14). */
static int relax(column *c, const mpm_material_params *par)
{
  mpm_nonlocal *ws = NULL;
  mpm_err err = {0};
  mpm_points *P = mpm_points_alloc(c->n);            /* the points' positions, to locate */
  for (size_t k = 0; P && k < c->n; k++) {
    size_t q;
    if (mpm_points_push(P, &q) != MPM_OK)
      break;
    P->x[q] = c->x[k];
    P->y[q] = c->y[k];
  }
  if (!P || P->n != c->n ||
      mpm_nonlocal_alloc(&ws, &c->m, c->edge, MPM_NONLOCAL_CENTRE, c->n, &err) != MPM_OK ||
      mpm_nonlocal_locate(ws, &c->m, P, &err) != MPM_OK) {
    printf("  %s\n", P ? err.msg : "out of memory");
    mpm_nonlocal_free(ws);
    mpm_points_free(P);
    return -1;
  }
  mpm_points_free(P);
  for (size_t k = 0; k < c->n; k++)
    ws->dense[k] = 1;
  double h = fmin(c->m.dx, c->m.dy);
  double dt = 0.9 * h * h * par->t0 / (4.0 * par->A * par->A * par->d * par->d);  /* number 0.9 */
  double kD = dt / par->t0 * par->A * par->A * par->d * par->d, change = 1.0;
  for (long it = 0; it < 100000000L && change > 1e-14; it++) {
    mpm_nonlocal_average(ws, c->n, c->mass, c->g, ws->dense);
    mpm_nonlocal_laplacian(ws);
    if (par->p_sample == MPM_NGF_P_UNIT)
      mpm_nonlocal_pressure(ws, c->n, c->mass, c->p, ws->dense);
    change = 0.0;
    for (size_t k = 0; k < c->n; k++) {
      double tau_tr = c->mu[k] * (c->p[k] + par->G * dt * c->g[k]);   /* mu(x = g) = mu */
      double gs = fmax(0.0, c->g[k] + kD * mpm_nonlocal_point_lap(ws, k));
      double x = mpm_material_ngf_fluidity(par, dt, c->p[k], tau_tr, gs, c->mu[k] * c->g[k],
                                           mpm_nonlocal_point_isp(ws, k));
      change = fmax(change, fabs(x - c->g[k]) / fmax(x, 1e-300));
      c->g[k] = x;
    }
  }
  mpm_nonlocal_free(ws);
  return 0;
}

/* Reference g at coordinate q by linear interpolation (nodes in any order). */
static double ref_at(const ngf1d_result *r, double q)
{
  int lo = 0, hi = r->n, up = r->pos[r->n] > r->pos[0];
  while (hi - lo > 1) {
    int mid = (lo + hi) / 2;
    if ((r->pos[mid] <= q) == up)
      lo = mid;
    else
      hi = mid;
  }
  double t = (q - r->pos[lo]) / (r->pos[hi] - r->pos[lo]);
  return r->g[lo] + t * (r->g[hi] - r->g[lo]);
}

/* max |g - g_ref| / max g_ref over the column's first row (chute: column 0). */
static double error_vs(const column *c, const ngf1d_result *ref, int along_y)
{
  double e = 0.0, gm = 0.0;
  for (int i = 0; i <= ref->n; i++)
    gm = fmax(gm, ref->g[i]);
  int n = along_y ? c->m.ny : c->m.nx, stride = along_y ? c->m.nx : 1;
  for (int k = 0; k < n; k++) {
    size_t q = (size_t)k * (size_t)stride;
    double pos = along_y ? c->y[q] : fabs(c->x[q]);
    e = fmax(e, fabs(c->g[q] - ref_at(ref, pos)));
  }
  return e / gm;
}

/* Chute column with ny units over the depth (2 units along the slope). */
static double chute_error(const ngf1d_problem *pb, const ngf1d_result *ref, int ny, int sample)
{
  double dy = pb->H / ny, kap = pb->rho * pb->grav * cos(pb->theta);
  column c = {.m = {.nx = 2, .ny = ny, .dx = dy, .dy = dy, .periodic_x = 1},
              .edge = {MPM_BC_PERIODIC, MPM_BC_PERIODIC, MPM_BC_NOSLIP, MPM_BC_FREE}};
  mpm_material_params par = params_of(pb, sample);
  double e = NAN;
  if (column_alloc(&c) == 0) {
    for (size_t k = 0; k < c.n; k++) {
      c.p[k] = pb->p_top + kap * (pb->H - c.y[k]);               /* p(z) */
      c.mu[k] = tan(pb->theta);
    }
    if (relax(&c, &par) == 0)
      e = error_vs(&c, ref, 1);
  }
  column_free(&c);
  return e;
}

/* Vertical chute with nx units across the width (2 along the flow). */
static double vchute_error(const ngf1d_problem *pb, const ngf1d_result *ref, int nx, int sample)
{
  double dx = pb->L / nx;
  column c = {.m = {.nx = nx, .ny = 2, .x0 = -0.5 * pb->L, .dx = dx, .dy = dx, .periodic_y = 1},
              .edge = {MPM_BC_NOSLIP, MPM_BC_NOSLIP, MPM_BC_PERIODIC, MPM_BC_PERIODIC}};
  mpm_material_params par = params_of(pb, sample);
  double e = NAN;
  if (column_alloc(&c) == 0) {
    for (size_t k = 0; k < c.n; k++) {
      c.p[k] = pb->p;
      c.mu[k] = pb->rho * pb->grav * fabs(c.x[k]) / pb->p;       /* rho grav |x| / p */
    }
    if (relax(&c, &par) == 0)
      e = error_vs(&c, ref, 0);
  }
  column_free(&c);
  return e;
}

/* Refinement study: errors on n0, 2 n0, ... and the checks on the last level. */
static void study(tally *t, const char *name, const ngf1d_problem *pb, int sample, int n0,
                  int levels, double emax, double olo, double ohi)
{
  ngf1d_problem fine = *pb;
  fine.n = 6400;
  ngf1d_result ref;
  char msg[256], label[128];
  if (ngf1d_solve(&fine, NULL, &ref, msg, sizeof msg) || ref.trivial) {
    printf("  reference: %s\n", ref.trivial ? "no flow" : msg);
    report(t, name, NAN, 0, 0);
    ngf1d_result_free(&ref);
    return;
  }
  double e[8];
  for (int k = 0; k < levels; k++) {
    int n = n0 << k;
    e[k] = pb->geometry == NGF1D_CHUTE ? chute_error(pb, &ref, n, sample)
                                       : vchute_error(pb, &ref, n, sample);
    printf("  %s, %d units: max|g - g_ref| / max g_ref = %.4g\n", name, n, e[k]);
  }
  snprintf(label, sizeof label, "%s: error at %d units", name, n0 << (levels - 1));
  report(t, label, e[levels - 1], 0.0, emax);
  snprintf(label, sizeof label, "%s: order, %d -> %d units", name, n0 << (levels - 2),
           n0 << (levels - 1));
  report(t, label, log2(e[levels - 2] / e[levels - 1]), olo, ohi);
  ngf1d_result_free(&ref);
}

int main(int argc, char **argv)
{
  tally t = {0, argc > 1 && strcmp(argv[1], "--quick") == 0};
  ngf1d_problem pb;
  for (int form = NGF1D_DK; form <= NGF1D_HS21; form++) {
    ngf1d_defaults(&pb, NGF1D_CHUTE);
    pb.form = form;
    pb.H = 3.0 * ngf1d_hstop(&pb);
    pb.p_top = 50.0;
    study(&t, form == NGF1D_DK ? "chute dk, H = 3 Hstop, p_top = 50 Pa"
                               : "chute hs21, H = 3 Hstop, p_top = 50 Pa",
          &pb, MPM_NGF_P_UNIT, 10, t.quick ? 4 : 5, t.quick ? 2e-4 : 6e-5, 1.9, 2.1);
  }
  ngf1d_defaults(&pb, NGF1D_VCHUTE);
  study(&t, "vchute hs21 [D-thesis]", &pb, MPM_NGF_P_UNIT, 80, t.quick ? 3 : 4, t.quick ? 3e-3 : 8e-4, 1.9, 2.1);
  pb.form = NGF1D_DK;
  pb.p = 15000.0;
  pb.d = 0.01;
  study(&t, "vchute dk, p = 15 kPa, d = 1 cm", &pb, MPM_NGF_P_UNIT, 80, t.quick ? 3 : 4, t.quick ? 3e-3 : 8e-4,
        1.9, 2.2);
  ngf1d_defaults(&pb, NGF1D_CHUTE);
  study(&t, "chute dk, free surface, p sampled per point", &pb, MPM_NGF_P_POINT, 20, 3, 0.05,
        0.35, 0.65);
  study(&t, "chute dk, free surface, p sampled per unit", &pb, MPM_NGF_P_UNIT, 20, 3, 1e-3,
        1.4, 2.1);
  printf("ngf1d kernels: %s (%d target(s) missed)\n", t.fails ? "FAIL" : "PASS", t.fails);
  return t.fails;
}
