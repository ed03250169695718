/* selftest.c: checks of the steady 1D NGF reference solver (ngf1d.h).
 *
 * 1. Second-order convergence under grid refinement: chute ([DK-silo] form,
 *    H = 3 Hstop) and vertical chute ([D-thesis] values, linearised form; the
 *    [DK-silo] form; the linear kk equation of [D-thesis] with either wall
 *    condition): observed orders of max|g_n - g_2n| and max|v_n - v_2n|
 *    on the coarse nodes, the last two levels within 2 +- 0.1.
 * 2. Hstop ([DK-silo] eq. 3.1): the discrete threshold of the linear operator
 *    converges to it at second order; the nonlinear solver finds g = 0 only at
 *    H = 0.98 and 0.995 Hstop and a flowing solution at 1.005 and 1.02 Hstop,
 *    for both PDE forms.
 * 3. Near Hstop: the amplitude grows linearly in H - Hstop (transcritical
 *    bifurcation) and v/v(H) -> 1 - cos(pi z / 2H), the deviation ~ H/Hstop - 1.
 * 4. H >> Hstop: v/v(H) -> 1 - (1 - z/H)^1.5 (Bagnold) and the surface velocity
 *    -> the local value ([DK15] eq. 4.6), deviations ~ Hstop/H.
 * 5. Vertical chute with small A -> the local (plug and shear zone) profile.
 * Prints "name measured target PASS|FAIL"; exit status = number of failures.
 * --quick uses fewer refinement levels. */
#define _DEFAULT_SOURCE /* M_PI */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ngf1d.h"

typedef struct tally { int fails, quick; } tally;

static void report(tally *t, const char *name, double measured, double lo, double hi)
{
  int ok = measured >= lo && measured <= hi;
  printf("%-58s %12.5g  in [%g, %g]  %s\n", name, measured, lo, hi, ok ? "PASS" : "FAIL");
  t->fails += !ok;
}

static int solve(const ngf1d_problem *pb, ngf1d_result *r)
{
  char msg[256];
  int rc = ngf1d_solve(pb, NULL, r, msg, sizeof msg);
  if (rc)
    printf("  solver: %s\n", msg);
  return rc;
}

/* max over the coarse nodes of |a - b| with b on the twice finer grid. */
static double diff_coarse(const double *a, const double *b, int n)
{
  double m = 0.0;
  for (int i = 0; i <= n; i++)
    m = fmax(m, fabs(a[i] - b[2 * i]));
  return m;
}

/* ---- 1. convergence order ----------------------------------------------- */

static void order(tally *t, const char *name, ngf1d_problem pb, int n0, int levels)
{
  ngf1d_result r[8];
  double eg[8] = {0}, ev[8] = {0};
  memset(r, 0, sizeof r);
  int ok = 1;
  for (int k = 0; k < levels && ok; k++) {
    pb.n = n0 << k;
    ok = solve(&pb, &r[k]) == 0 && !r[k].trivial;
    if (ok && k > 0) {
      eg[k] = diff_coarse(r[k - 1].g, r[k].g, r[k - 1].n);
      ev[k] = diff_coarse(r[k - 1].v, r[k].v, r[k - 1].n);
    }
  }
  char label[96];
  for (int k = levels - 2; k < levels && ok; k++) {
    snprintf(label, sizeof label, "%s: order of g, n = %d..%d", name, n0 << (k - 2), n0 << k);
    report(t, label, log2(eg[k - 1] / eg[k]), 1.9, 2.1);
    snprintf(label, sizeof label, "%s: order of v, n = %d..%d", name, n0 << (k - 2), n0 << k);
    report(t, label, log2(ev[k - 1] / ev[k]), 1.9, 2.1);
  }
  if (!ok)
    report(t, name, NAN, 0, 0);
  for (int k = 0; k < levels; k++)
    ngf1d_result_free(&r[k]);
}

static void check_orders(tally *t)
{
  int lv = t->quick ? 5 : 7;
  ngf1d_problem pb;
  ngf1d_defaults(&pb, NGF1D_CHUTE);
  order(t, "chute dk, H = 3 Hstop", pb, 50, lv);
  ngf1d_defaults(&pb, NGF1D_VCHUTE);
  order(t, "vchute hs21 [D-thesis]", pb, 100, lv);
  pb.form = NGF1D_DK;
  pb.p = 15000.0;
  pb.d = 0.01;
  order(t, "vchute dk, p = 15 kPa, d = 1 cm", pb, 100, lv);
  ngf1d_defaults(&pb, NGF1D_VCHUTE);              /* [D-thesis] Table 4.1, b = 18.754 */
  pb.equation = NGF1D_EQ_KK;
  pb.I0 = (pb.mu_2 - pb.mu_s) / 18.754;
  pb.wall_neumann = 1;
  order(t, "vchute kk [D-thesis] eq. 2.29, g' = 0 at walls", pb, 100, lv);
  pb.wall_neumann = 0;
  order(t, "vchute kk [D-thesis] eq. 2.29, g = 0 at walls", pb, 100, lv);
}

/* ---- 2. Hstop ------------------------------------------------------------- */

static void check_hstop_linear(tally *t, int form)
{
  ngf1d_problem pb;
  ngf1d_defaults(&pb, NGF1D_CHUTE);
  pb.form = form;
  double hs = ngf1d_hstop(&pb), e[4];
  for (int k = 0; k < 4; k++) {
    pb.n = 100 << k;
    e[k] = fabs(ngf1d_hstop_discrete(&pb) / hs - 1.0);
  }
  char label[96];
  const char *f = form == NGF1D_DK ? "dk" : "hs21";
  snprintf(label, sizeof label, "Hstop %s: discrete/analytic - 1, n = 800", f);
  report(t, label, e[3], 0.0, 1e-6);
  snprintf(label, sizeof label, "Hstop %s: order of the discrete threshold", f);
  report(t, label, log2(e[2] / e[3]), 1.9, 2.1);
}

/* max g of the solution at H = rel Hstop, or -1 on failure; *v0 its surface v. */
static double chute_at(int form, double rel, int n, ngf1d_result *keep)
{
  ngf1d_problem pb;
  ngf1d_defaults(&pb, NGF1D_CHUTE);
  pb.form = form;
  pb.n = n;
  pb.H = rel * ngf1d_hstop(&pb);
  ngf1d_result r;
  if (solve(&pb, &r)) {
    ngf1d_result_free(&r);
    return -1.0;
  }
  double m = r.trivial ? 0.0 : r.g[0];   /* g is largest at the free surface */
  for (int i = 0; i <= r.n; i++)
    m = fmax(m, r.g[i]);
  if (keep)
    *keep = r;
  else
    ngf1d_result_free(&r);
  return m;
}

static void check_threshold(tally *t, int form)
{
  const double rel[4] = {0.98, 0.995, 1.005, 1.02};
  char label[96];
  for (int k = 0; k < 4; k++) {
    double m = chute_at(form, rel[k], 400, NULL);
    snprintf(label, sizeof label, "H = %.3f Hstop (%s): max g [1/s]", rel[k],
             form == NGF1D_DK ? "dk" : "hs21");
    if (rel[k] < 1.0)
      report(t, label, m, 0.0, 0.0);                 /* only g = 0 */
    else
      report(t, label, m, 1e-4, INFINITY);           /* flows */
  }
}

/* ---- 3. near Hstop ---------------------------------------------------------- */

/* max |v/v(H) - shape(z/H)| of a chute solution. */
static double shape_dev(const ngf1d_result *r, int bagnold)
{
  double H = r->pos[0], vs = r->v[0], m = 0.0;
  for (int i = 0; i <= r->n; i++) {
    double zh = r->pos[i] / H;
    double ref = bagnold ? 1.0 - pow(1.0 - zh, 1.5) : 1.0 - cos(0.5 * M_PI * zh);
    m = fmax(m, fabs(r->v[i] / vs - ref));
  }
  return m;
}

static void check_near(tally *t)
{
  ngf1d_result a, b, c;
  double ma = chute_at(NGF1D_DK, 1.005, 400, &a), mb = chute_at(NGF1D_DK, 1.02, 400, &b);
  double mc = chute_at(NGF1D_DK, 1.001, 400, &c);
  if (ma <= 0.0 || mb <= 0.0 || mc <= 0.0) {
    report(t, "near Hstop: solutions", NAN, 0, 0);
    return;
  }
  report(t, "near Hstop: max g(1.02 Hstop) / max g(1.005 Hstop)", mb / ma, 3.8, 4.2);
  report(t, "near Hstop: |v/v(H) - (1 - cos(pi z/2H))|, H = 1.001 Hstop", shape_dev(&c, 0), 0, 1e-4);
  report(t, "near Hstop: same deviation / (H/Hstop - 1), 1.02 vs 1.005",
         (shape_dev(&b, 0) / 0.02) / (shape_dev(&a, 0) / 0.005), 0.95, 1.05);
  ngf1d_result_free(&a);
  ngf1d_result_free(&b);
  ngf1d_result_free(&c);
}

/* ---- 4. H >> Hstop ---------------------------------------------------------- */

static void check_bagnold(tally *t)
{
  const double rel[2] = {20.0, 100.0};
  double dev[2], vr[2];
  for (int k = 0; k < 2; k++) {
    ngf1d_result r;
    ngf1d_problem pb;
    ngf1d_defaults(&pb, NGF1D_CHUTE);
    pb.H = rel[k] * ngf1d_hstop(&pb);
    pb.n = 1600;
    if (solve(&pb, &r) || r.trivial) {
      report(t, "Bagnold: solution", NAN, 0, 0);
      ngf1d_result_free(&r);
      return;
    }
    dev[k] = shape_dev(&r, 1);
    vr[k] = r.v[0] / ngf1d_local_v(&pb, pb.H);
    ngf1d_result_free(&r);
  }
  report(t, "H = 100 Hstop: |v/v(H) - (1 - (1 - z/H)^1.5)|", dev[1], 0.0, 0.015);
  report(t, "H = 20 -> 100 Hstop: that deviation shrinks by", dev[0] / dev[1], 3.5, 6.0);
  report(t, "H = 100 Hstop: 1 - v(H) / v_local(H) (Bagnold)", 1.0 - vr[1], 0.0, 0.03);
  report(t, "H = 20 -> 100 Hstop: that deficit shrinks by", (1.0 - vr[0]) / (1.0 - vr[1]),
         3.5, 6.0);
}

/* ---- 5. vertical chute, small A --------------------------------------------- */

static double vchute_local_dev(double A)
{
  ngf1d_problem pb;
  ngf1d_defaults(&pb, NGF1D_VCHUTE);
  pb.A = A;
  pb.n = 3200;
  ngf1d_result r;
  if (solve(&pb, &r) || r.trivial) {
    ngf1d_result_free(&r);
    return NAN;
  }
  double m = 0.0, v0 = ngf1d_local_v(&pb, 0.0);
  for (int i = 0; i <= r.n; i++)
    m = fmax(m, fabs(r.v[i] - ngf1d_local_v(&pb, r.pos[i])));
  ngf1d_result_free(&r);
  return m / v0;
}

static void check_vchute_local(tally *t)
{
  double a = vchute_local_dev(0.04), b = vchute_local_dev(0.01);
  report(t, "vchute, A = 0.01: max|v - v_local| / v_local(0)", b, 0.0, 0.002);
  report(t, "vchute: that deviation, A = 0.04 over A = 0.01 (~ A)", a / b, 3.5, 4.5);
}

int main(int argc, char **argv)
{
  tally t = {0, argc > 1 && strcmp(argv[1], "--quick") == 0};
  check_orders(&t);
  check_hstop_linear(&t, NGF1D_DK);
  check_hstop_linear(&t, NGF1D_HS21);
  check_threshold(&t, NGF1D_DK);
  check_threshold(&t, NGF1D_HS21);
  check_near(&t);
  check_bagnold(&t);
  check_vchute_local(&t);
  printf("ngf1d: %s (%d target(s) missed)\n", t.fails ? "FAIL" : "PASS", t.fails);
  return t.fails;
}
