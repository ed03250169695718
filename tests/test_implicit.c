/* test_implicit.c: backward-Euler diffusion of the element fluidity
 * (src/nonlocal/implicit.c; docs/model.md, "Implicit diffusion"), tested
 * from the equations:
 *   - on a periodic grid, L_h cos(k . x) = -lambda cos(k . x) with
 *     lambda = (2 - 2 cos(kx dx))/dx^2 + (2 - 2 cos(ky dy))/dy^2, so each
 *     step of (I - c L_h) g* = g multiplies the mode by 1/(1 + c lambda);
 *   - with g independent of the other axis, a Dirichlet (no-slip) edge, a
 *     Neumann edge (free edge, or empty units) give the 1D tridiagonal
 *     system, solved here by the Thomas algorithm;
 *   - g* solves (I - c L_h) g* = g_e with L_h the explicit operator
 *     (mpm_nonlocal_laplacian) on grids with holes and every kind of edge
 *     (a periodic axis of two units: both neighbours are one unit),
 *     lap_e = (g* - g_e)/c equals L_h g*, and g* >= 0 for g_e >= 0;
 *   - the factorisation is reused while the filled set and c stay, redone
 *     numerically when c changes and symbolically when the set changes;
 *   - c = 0 is the explicit Laplacian bitwise; an empty set, c < 0 and a
 *     grid of another size are errors. */
#define _DEFAULT_SOURCE /* M_PI */
#include <check.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/config.h"
#include "mesh/mesh.h"
#include "nonlocal/implicit.h"
#include "nonlocal/nonlocal.h"

enum { LEFT = 0, RIGHT, BOTTOM, TOP };

static mpm_mesh make_mesh(int nx, int ny, double dx, double dy, int px, int py)
{
  mpm_mesh m = {.nx = nx, .ny = ny, .x0 = 0.2, .y0 = -0.4, .dx = dx, .dy = dy,
                .topology = MPM_TOPO_Q4, .periodic_x = px, .periodic_y = py};
  mpm_err err = {0};
  ck_assert_int_eq(mpm_mesh_setup(&m, &err), MPM_OK);
  return m;
}

static mpm_nonlocal *make_ws(const mpm_mesh *m, const int edge[4])
{
  mpm_nonlocal *ws = NULL;
  mpm_err err = {0};
  ck_assert_int_eq(mpm_nonlocal_alloc(&ws, m, edge, MPM_NONLOCAL_CENTRE, 4, &err), MPM_OK);
  return ws;
}

static mpm_nonlocal_implicit *make_im(const mpm_nonlocal *ws)
{
  mpm_err err = {0};
  mpm_nonlocal_implicit *im = mpm_nonlocal_implicit_alloc(ws, &err);
  ck_assert_msg(im != NULL, "%s", err.msg);
  return im;
}

static double lcg(unsigned long *s)
{
  *s = *s * 6364136223846793005UL + 1442695040888963407UL;
  return (double)(*s >> 11) / 9007199254740992.0;
}

/* Round-off bound for g* of (I - c L_h) g* = g: 10 eps times the condition
 * number bound 1 + c lambda_max, lambda_max = 4/dx^2 + 4/dy^2. */
static double roundoff(double c, double dx, double dy)
{
  return 10.0 * DBL_EPSILON * (1.0 + c * (4.0 / (dx * dx) + 4.0 / (dy * dy)));
}

static int solve(mpm_nonlocal_implicit *im, mpm_nonlocal *ws, double c)
{
  mpm_err err = {0};
  int rc = mpm_nonlocal_implicit_laplacian(im, ws, c, &err);
  ck_assert_msg(rc == MPM_OK, "%s", err.msg);
  return rc;
}

/* ------------------------------------------------------------------ */

/* g = g0 + a cos(kx x) + b cos(kx2 x) cos(ky y): each mode decays per step
 * by 1/(1 + c lambda) (the constant by 1), over several steps, c far beyond
 * the explicit limit. */
START_TEST(t_periodic_cosine_decay)
{
  const int nx = 16, ny = 12, nsteps = 4;
  const double dx = 0.05, dy = 0.03;
  mpm_mesh m = make_mesh(nx, ny, dx, dy, 1, 1);
  int edge[4] = {MPM_BC_PERIODIC, MPM_BC_PERIODIC, MPM_BC_PERIODIC, MPM_BC_PERIODIC};
  mpm_nonlocal *ws = make_ws(&m, edge);
  mpm_nonlocal_implicit *im = make_im(ws);
  const double kx = 2.0 * M_PI * 3.0 / (nx * dx), kx2 = 2.0 * M_PI * 5.0 / (nx * dx);
  const double ky = 2.0 * M_PI * 2.0 / (ny * dy);
  const double lx = (2.0 - 2.0 * cos(kx * dx)) / (dx * dx);
  const double lxy = (2.0 - 2.0 * cos(kx2 * dx)) / (dx * dx) + (2.0 - 2.0 * cos(ky * dy)) / (dy * dy);
  const double c = 40.0 / (2.0 / (dx * dx) + 2.0 / (dy * dy));  /* 40 x the explicit limit */
  const double tol = roundoff(c, dx, dy);
  const double g0 = 2.0;
  double a = 0.7, b = 0.4, worst = 0.0, worst_lap = 0.0, worst_amp = 0.0, first_rate = 0.0;
  const size_t nu = (size_t)nx * ny;
  double *fa = malloc(nu * sizeof *fa), *fb = malloc(nu * sizeof *fb), *lap = malloc(nu * sizeof *lap);
  double na = 0.0, nb = 0.0;
  for (int j = 0; j < ny; j++)
    for (int i = 0; i < nx; i++) {
      const size_t e = (size_t)i + (size_t)nx * j;
      const double x = (i + 0.5) * dx, y = (j + 0.5) * dy;
      fa[e] = cos(kx * x);
      fb[e] = cos(kx2 * x) * cos(ky * y);
      na += fa[e] * fa[e];
      nb += fb[e] * fb[e];
      ws->sm[e] = 1.0;
      ws->ge[e] = g0 + a * fa[e] + b * fb[e];
    }
  for (int step = 0; step < nsteps; step++) {  /* g_e of each step: g* of the one before */
    solve(im, ws, c);
    const double *gs = mpm_nonlocal_implicit_gstar(im);
    double pa1 = 0.0, pa0 = 0.0, pb1 = 0.0, pb0 = 0.0;  /* projections on the modes */
    for (size_t e = 0; e < nu; e++) {
      pa1 += gs[e] * fa[e];
      pa0 += ws->ge[e] * fa[e];
      pb1 += gs[e] * fb[e];
      pb0 += ws->ge[e] * fb[e];
    }
    const double ra = 1.0 / (1.0 + c * lx), rb = 1.0 / (1.0 + c * lxy);  /* the decay factors */
    if (step == 0)
      first_rate = fmax(fabs(pa1 / pa0 / ra - 1.0), fabs(pb1 / pb0 / rb - 1.0));
    worst_amp = fmax(worst_amp, fabs(pa1 - ra * pa0) / na / g0);  /* amplitude error / g0 */
    worst_amp = fmax(worst_amp, fabs(pb1 - rb * pb0) / nb / g0);
    a *= ra;
    b *= rb;
    for (size_t e = 0; e < nu; e++)
      worst = fmax(worst, fabs(gs[e] - (g0 + a * fa[e] + b * fb[e])) / g0);
    /* lap = (g* - g_e)/c is L_h g*: the explicit Laplacian of g* */
    memcpy(lap, ws->lap, nu * sizeof *lap);
    memcpy(ws->ge, gs, nu * sizeof *gs);
    mpm_nonlocal_laplacian(ws);
    for (size_t e = 0; e < nu; e++)          /* as an increment c lap to g */
      worst_lap = fmax(worst_lap, c * fabs(lap[e] - ws->lap[e]) / g0);
  }
  printf("periodic cosine decay (c lambda = %.4g, %.4g; bound %.3g):\n"
         "  relative error of the first step's decay factors 1/(1 + c lambda): %.3g\n"
         "  over %d steps: decayed amplitude error / g0 %.3g, max |g* - exact| / g0 %.3g,\n"
         "  max c |lap - L_h g*| / g0 %.3g\n", c * lx, c * lxy, tol, first_rate, nsteps,
         worst_amp, worst, worst_lap);
  ck_assert_msg(first_rate < tol, "decay factor error %g", first_rate);
  ck_assert_msg(worst_amp < tol, "decayed amplitude error %g", worst_amp);
  ck_assert_msg(worst < tol, "decay error %g (bound %g)", worst, tol);
  ck_assert_msg(worst_lap < tol, "lap identity error %g", worst_lap);
  mpm_linalg_stats st = mpm_nonlocal_implicit_stats(im);
  ck_assert_int_eq(st.analyses, 1);
  ck_assert_int_eq(st.factors, 1);
  ck_assert_int_eq(st.solves, nsteps);
  ck_assert_int_eq(st.fallbacks, 0);
  free(fa);
  free(fb);
  free(lap);
  mpm_nonlocal_implicit_free(im);
  mpm_nonlocal_free(ws);
}
END_TEST

/* The 1D system with n unknowns, spacing h, ends lo and hi (+1 Neumann,
 * -1 Dirichlet): (1 + 2 c/h^2 - c (k_lo or k_hi)/h^2) on the diagonal at the
 * ends, -c/h^2 off it; solved by the Thomas algorithm into x. */
static void thomas_1d(int n, double h, double c, int klo, int khi, const double *f, double *x)
{
  if (n < 1)
    return;
  double *cp = malloc(n * sizeof *cp), *dp = malloc(n * sizeof *dp);
  const double off = -c / (h * h);
  for (int i = 0; i < n; i++) {
    double diag = 1.0 + 2.0 * c / (h * h);
    if (i == 0)
      diag -= klo * c / (h * h);             /* ghost k g_0 */
    if (i == n - 1)
      diag -= khi * c / (h * h);
    double den = i > 0 ? diag - off * cp[i - 1] : diag;
    cp[i] = off / den;
    dp[i] = (f[i] - (i > 0 ? off * dp[i - 1] : 0.0)) / den;
  }
  x[n - 1] = dp[n - 1];
  for (int i = n - 2; i >= 0; i--)
    x[i] = dp[i] - cp[i] * x[i + 1];
  free(cp);
  free(dp);
}

static int ghost_k(int bc)
{
  return bc == MPM_BC_NOSLIP ? -1 : 1;
}

/* g = f(coordinate along axis) on a strip, the other axis periodic (axis y)
 * or between frictionless walls (axis x); units from nfill on along the axis
 * are empty (a Neumann face). Returns max |g* - 1D solution| / max |g|. */
static double strip_error(int axis, int lo, int hi, int nfill, double c_factor, double *tol)
{
  const int nl = 24, nt = 3;                 /* along, across */
  const double h = 0.0175, ht = 0.021;
  const int nx = axis == 0 ? nl : nt, ny = axis == 0 ? nt : nl;
  const double dx = axis == 0 ? h : ht, dy = axis == 0 ? ht : h;
  mpm_mesh m = make_mesh(nx, ny, dx, dy, axis == 1, 0);
  int edge[4];
  if (axis == 0) {
    edge[LEFT] = lo;
    edge[RIGHT] = hi;
    edge[BOTTOM] = edge[TOP] = MPM_BC_FRICTIONLESS;
  } else {
    edge[LEFT] = edge[RIGHT] = MPM_BC_PERIODIC;
    edge[BOTTOM] = lo;
    edge[TOP] = hi;
  }
  mpm_nonlocal *ws = make_ws(&m, edge);
  mpm_nonlocal_implicit *im = make_im(ws);
  double f[24], x[24];
  for (int a = 0; a < nl; a++)
    f[a] = 1.0 + 0.3 * a / nl + 0.8 * sin(0.45 * a) * sin(0.45 * a);
  for (int j = 0; j < ny; j++)
    for (int i = 0; i < nx; i++) {
      int a = axis == 0 ? i : j, e = i + nx * j;
      ws->sm[e] = a < nfill ? 1.0 + 0.1 * i : 0.0;
      ws->ge[e] = a < nfill ? f[a] : 0.0;
    }
  const double c = c_factor * h * h;
  *tol = roundoff(c, h, h);
  solve(im, ws, c);
  thomas_1d(nfill, h, c, ghost_k(lo), nfill < nl ? 1 : ghost_k(hi), f, x);
  const double *gs = mpm_nonlocal_implicit_gstar(im);
  double err = 0.0, fmaxv = 0.0;
  for (int a = 0; a < nfill; a++)
    fmaxv = fmax(fmaxv, fabs(f[a]));
  for (int j = 0; j < ny; j++)
    for (int i = 0; i < nx; i++) {
      int a = axis == 0 ? i : j, e = i + nx * j;
      if (a < nfill)
        err = fmax(err, fabs(gs[e] - x[a]) / fmaxv);
      else
        ck_assert(gs[e] == 0.0 && ws->lap[e] == 0.0);
    }
  ck_assert_int_eq(mpm_nonlocal_implicit_stats(im).fallbacks, 0);
  mpm_nonlocal_implicit_free(im);
  mpm_nonlocal_free(ws);
  return err;
}

START_TEST(t_1d_dirichlet_neumann)
{
  const int D = MPM_BC_NOSLIP, N = MPM_BC_FREE, S = MPM_BC_SYMMETRY;
  struct {
    int axis, lo, hi, nfill;
    const char *what;
  } cases[] = {
      {0, D, N, 24, "x: no-slip left, free right"},
      {0, N, D, 24, "x: free left, no-slip right"},
      {0, D, D, 24, "x: no-slip both"},
      {0, S, N, 24, "x: symmetry left, free right"},
      {0, D, D, 17, "x: no-slip left, empty units from 17"},
      {1, D, N, 24, "y: no-slip bottom, free top (x periodic)"},
      {1, D, N, 11, "y: no-slip bottom, empty units from 11"},
  };
  const double cf[] = {0.1, 3.0, 400.0};     /* c / h^2 */
  double worst = 0.0;
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++)
    for (size_t q = 0; q < 3; q++) {
      double tol = 0.0;
      double e = strip_error(cases[k].axis, cases[k].lo, cases[k].hi, cases[k].nfill, cf[q], &tol);
      printf("1D %-42s c/h^2 = %5g: max |g* - Thomas| / max g = %.3g (bound %.3g)\n",
             cases[k].what, cf[q], e, tol);
      ck_assert_msg(e < tol, "%s, c/h^2 = %g: error %g", cases[k].what, cf[q], e);
      worst = fmax(worst, e);
    }
  printf("1D worst: %.3g\n", worst);
}
END_TEST

/* Holes, every edge kind, a periodic axis of 2 units: g* - c L_h g* = g_e
 * with the explicit L_h, lap = L_h g*, g* >= 0, Cholesky (no fallback). */
START_TEST(t_matches_explicit_operator)
{
  struct {
    int nx, ny, px, py, edge[4];
  } cases[] = {
      {11, 7, 0, 0, {MPM_BC_NOSLIP, MPM_BC_FREE, MPM_BC_NOSLIP, MPM_BC_FRICTIONLESS}},
      {9, 8, 1, 0, {MPM_BC_PERIODIC, MPM_BC_PERIODIC, MPM_BC_NOSLIP, MPM_BC_FREE}},
      {7, 9, 0, 1, {MPM_BC_SYMMETRY, MPM_BC_NOSLIP, MPM_BC_PERIODIC, MPM_BC_PERIODIC}},
      {2, 6, 1, 0, {MPM_BC_PERIODIC, MPM_BC_PERIODIC, MPM_BC_NOSLIP, MPM_BC_NOSLIP}},
      {5, 2, 1, 1, {MPM_BC_PERIODIC, MPM_BC_PERIODIC, MPM_BC_PERIODIC, MPM_BC_PERIODIC}},
  };
  unsigned long seed = 7;
  double worst = 0.0, worst_lap = 0.0, tol = INFINITY;
  for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
    const double dx = 0.013, dy = 0.021;
    mpm_mesh m = make_mesh(cases[k].nx, cases[k].ny, dx, dy, cases[k].px, cases[k].py);
    mpm_nonlocal *ws = make_ws(&m, cases[k].edge);
    mpm_nonlocal_implicit *im = make_im(ws);
    const size_t nu = (size_t)m.nx * m.ny;
    double *g = malloc(nu * sizeof *g), *lap = malloc(nu * sizeof *lap);
    for (size_t e = 0; e < nu; e++) {
      int hole = nu > 12 && lcg(&seed) < 0.25;
      ws->sm[e] = hole ? 0.0 : 0.5 + lcg(&seed);
      ws->ge[e] = hole ? 0.0 : 10.0 * lcg(&seed);
      g[e] = ws->ge[e];
    }
    const double c = 25.0 * dx * dx;
    solve(im, ws, c);
    memcpy(lap, ws->lap, nu * sizeof *lap);
    const double *gs = mpm_nonlocal_implicit_gstar(im);
    memcpy(ws->ge, gs, nu * sizeof *gs);     /* L_h g* by the explicit code */
    mpm_nonlocal_laplacian(ws);
    double gmax = 0.0;
    for (size_t e = 0; e < nu; e++)
      gmax = fmax(gmax, g[e]);
    tol = fmin(tol, roundoff(c, dx, dy));
    for (size_t e = 0; e < nu; e++) {
      if (!(ws->sm[e] > 0.0)) {
        ck_assert(lap[e] == 0.0);
        continue;
      }
      ck_assert_msg(gs[e] >= 0.0, "case %zu: g* = %g < 0", k, gs[e]);
      double res = gs[e] - c * ws->lap[e] - g[e];   /* (I - c L_h) g* - g_e */
      worst = fmax(worst, fabs(res) / gmax);
      worst_lap = fmax(worst_lap, c * fabs(lap[e] - ws->lap[e]) / gmax);
    }
    ck_assert_int_eq(mpm_nonlocal_implicit_stats(im).fallbacks, 0);
    free(g);
    free(lap);
    mpm_nonlocal_implicit_free(im);
    mpm_nonlocal_free(ws);
  }
  printf("explicit operator: max |(I - c L_h) g* - g_e| / max g = %.3g, "
         "max c |lap - L_h g*| / max g = %.3g (bound %.3g)\n", worst, worst_lap, tol);
  ck_assert_msg(worst < tol, "residual %g", worst);
  ck_assert_msg(worst_lap < tol, "lap identity %g", worst_lap);
}
END_TEST

/* Analyses and factorisations. The system covers every unit filled so far,
 * so a unit that empties costs a factorisation, not an analysis: (1, 1)
 * over solves with one set and c, (1, 2) after c changes, (2, 3) when a unit
 * is filled for the first time (the cover grows), (2, 4) when it empties
 * again and (2, 5) when it fills again (both inside the cover). With the
 * unit empty again, its identity row is decoupled: g* and lap equal those of
 * a new solver that never covered it, to the round-off of another ordering
 * (roundoff()), and lap there is 0. c = 0 is the explicit lap bitwise and
 * touches no factor. */
START_TEST(t_factor_reuse)
{
  const int nx = 10, ny = 6;
  const double h = 0.02;
  mpm_mesh m = make_mesh(nx, ny, h, h, 1, 0);
  int edge[4] = {MPM_BC_PERIODIC, MPM_BC_PERIODIC, MPM_BC_NOSLIP, MPM_BC_FREE};
  mpm_nonlocal *ws = make_ws(&m, edge);
  mpm_nonlocal_implicit *im = make_im(ws);
  const size_t nu = (size_t)nx * ny;
  unsigned long seed = 3;
  for (size_t e = 0; e < nu; e++)
    ws->sm[e] = e == 17 ? 0.0 : 1.0;
  const double c = 0.01;
  for (int k = 0; k < 4; k++) {
    for (size_t e = 0; e < nu; e++)
      ws->ge[e] = e == 17 ? 0.0 : lcg(&seed);  /* new g_e every time */
    solve(im, ws, c);
  }
  mpm_linalg_stats st = mpm_nonlocal_implicit_stats(im);
  printf("reuse: same set and c: %ld analyses, %ld factorisations, %ld solves\n", st.analyses,
         st.factors, st.solves);
  ck_assert_int_eq(st.analyses, 1);
  ck_assert_int_eq(st.factors, 1);
  ck_assert_int_eq(st.solves, 4);
  solve(im, ws, 2.0 * c);
  solve(im, ws, 2.0 * c);
  st = mpm_nonlocal_implicit_stats(im);
  printf("reuse: after c changed: %ld analyses, %ld factorisations\n", st.analyses, st.factors);
  ck_assert_int_eq(st.analyses, 1);
  ck_assert_int_eq(st.factors, 2);
  ws->sm[17] = 1.0;                          /* filled for the first time */
  ws->ge[17] = 0.5;
  solve(im, ws, 2.0 * c);
  st = mpm_nonlocal_implicit_stats(im);
  printf("reuse: a unit filled for the first time: %ld analyses, %ld factorisations\n",
         st.analyses, st.factors);
  ck_assert_int_eq(st.analyses, 2);
  ck_assert_int_eq(st.factors, 3);
  ws->sm[17] = 0.0;                          /* empties again: inside the cover */
  ws->ge[17] = 0.0;
  solve(im, ws, 2.0 * c);
  solve(im, ws, 2.0 * c);
  st = mpm_nonlocal_implicit_stats(im);
  printf("reuse: after it emptied: %ld analyses, %ld factorisations\n", st.analyses,
         st.factors);
  ck_assert_int_eq(st.analyses, 2);
  ck_assert_int_eq(st.factors, 4);
  ck_assert_int_eq(st.solves, 9);
  ck_assert(ws->lap[17] == 0.0);
  /* the same solve by a solver that never covered unit 17 */
  double *lap = malloc(nu * sizeof *lap);
  memcpy(lap, ws->lap, nu * sizeof *lap);
  mpm_nonlocal_implicit *fresh = make_im(ws);
  solve(fresh, ws, 2.0 * c);
  const double *g1 = mpm_nonlocal_implicit_gstar(im), *g2 = mpm_nonlocal_implicit_gstar(fresh);
  double worst = 0.0;
  for (size_t e = 0; e < nu; e++) {
    worst = fmax(worst, fabs(g1[e] - g2[e]));
    worst = fmax(worst, 2.0 * c * fabs(lap[e] - ws->lap[e]));
  }
  printf("reuse: against a solver without the empty row: max |diff| %.3g (bound %.3g)\n", worst,
         roundoff(2.0 * c, h, h));
  ck_assert_msg(worst <= roundoff(2.0 * c, h, h), "%g", worst);
  ck_assert(g1[17] == 0.0);
  mpm_nonlocal_implicit_free(fresh);
  /* c = 0: the explicit Laplacian, bitwise; counts unchanged */
  mpm_nonlocal_laplacian(ws);
  memcpy(lap, ws->lap, nu * sizeof *lap);
  for (size_t e = 0; e < nu; e++)
    ws->lap[e] = NAN;
  solve(im, ws, 0.0);
  ck_assert(memcmp(lap, ws->lap, nu * sizeof *lap) == 0);
  st = mpm_nonlocal_implicit_stats(im);
  ck_assert_int_eq(st.factors, 4);
  ck_assert_int_eq(st.solves, 9);
  /* filled again: a factorisation, no analysis */
  ws->sm[17] = 1.0;
  solve(im, ws, 2.0 * c);
  st = mpm_nonlocal_implicit_stats(im);
  ck_assert_int_eq(st.analyses, 2);
  ck_assert_int_eq(st.factors, 5);
  free(lap);
  mpm_nonlocal_implicit_free(im);
  mpm_nonlocal_free(ws);
}
END_TEST

/* An outlet opens in a no-slip floor (mpm_nonlocal_open_faces): with g_e = 1
 * everywhere the explicit lap_e of a floor unit is 0 under an open face
 * (free surface, Neumann) and (-1 - 1)/dy^2 under a closed one (Dirichlet);
 * the implicit factor is redone (no new analysis: the same units) and
 * satisfies (I - c L_h) g* = g_e with the new L_h; a floor open along its
 * whole width gives the 1D Neumann solution. */
START_TEST(t_open_outlet)
{
  const int nx = 6, ny = 5;
  const double dx = 0.02, dy = 0.025, c = 30.0 * dx * dx;
  mpm_mesh m = make_mesh(nx, ny, dx, dy, 0, 0);
  int edge[4] = {MPM_BC_FRICTIONLESS, MPM_BC_FRICTIONLESS, MPM_BC_NOSLIP, MPM_BC_FREE};
  mpm_nonlocal *ws = make_ws(&m, edge);
  mpm_nonlocal_implicit *im = make_im(ws);
  const size_t nu = (size_t)nx * ny;
  for (size_t e = 0; e < nu; e++) {
    ws->sm[e] = 1.0;
    ws->ge[e] = 1.0;
  }
  const int cols[2][3] = {{2, 0, 0}, {4, 0, 0}}, none[3] = {0, 0, 0};
  mpm_nonlocal_open_faces(ws, BOTTOM, cols[0], cols[1], NULL, NULL);   /* columns 2 and 3 */
  mpm_nonlocal_laplacian(ws);
  for (int i = 0; i < nx; i++) {
    const double want = i == 2 || i == 3 ? 0.0 : -2.0 / (dy * dy);
    ck_assert_double_eq_tol(ws->lap[i], want, 1e-12 / (dy * dy));
    ck_assert_double_eq_tol(ws->lap[i + nx], 0.0, 1e-12 / (dy * dy));
  }
  mpm_nonlocal_open_faces(ws, -1, none, none, NULL, NULL);            /* closed again */
  solve(im, ws, c);
  unsigned long seed = 11;
  double *g = malloc(nu * sizeof *g);
  for (size_t e = 0; e < nu; e++)
    g[e] = ws->ge[e] = 1.0 + lcg(&seed);
  mpm_nonlocal_open_faces(ws, BOTTOM, cols[0], cols[1], NULL, NULL);
  solve(im, ws, c);
  mpm_linalg_stats st = mpm_nonlocal_implicit_stats(im);
  ck_assert_int_eq(st.analyses, 1);
  ck_assert_int_eq(st.factors, 2);
  const double *gs = mpm_nonlocal_implicit_gstar(im);
  memcpy(ws->ge, gs, nu * sizeof *gs);
  mpm_nonlocal_laplacian(ws);
  double worst = 0.0;
  for (size_t e = 0; e < nu; e++)
    worst = fmax(worst, fabs(gs[e] - c * ws->lap[e] - g[e]) / 2.0);
  printf("open outlet: max |(I - c L_h) g* - g_e| / max g = %.3g\n", worst);
  ck_assert_double_le(worst, roundoff(c, dx, dy));
  /* the whole floor open: every column is the 1D problem with Neumann ends */
  double f[5], x[5];
  for (int j = 0; j < ny; j++)
    for (int i = 0; i < nx; i++)
      ws->ge[i + nx * j] = f[j] = 1.0 + 0.5 * sin(0.9 * j);
  const int all[3] = {nx, 0, 0}, from[3] = {0, 0, 0};
  mpm_nonlocal_open_faces(ws, BOTTOM, from, all, NULL, NULL);
  solve(im, ws, c);
  thomas_1d(ny, dy, c, 1, 1, f, x);
  double err = 0.0;
  for (int j = 0; j < ny; j++)
    for (int i = 0; i < nx; i++)
      err = fmax(err, fabs(gs[i + nx * j] - x[j]) / 1.5);
  ck_assert_double_le(err, roundoff(c, dx, dy));
  free(g);
  mpm_nonlocal_implicit_free(im);
  mpm_nonlocal_free(ws);
}
END_TEST

/* No filled unit, c < 0 or not finite, another grid: errors; lap untouched;
 * the workspace still works afterwards. */
START_TEST(t_errors)
{
  mpm_mesh m = make_mesh(4, 3, 0.02, 0.02, 0, 0);
  int edge[4] = {MPM_BC_NOSLIP, MPM_BC_FREE, MPM_BC_NOSLIP, MPM_BC_FREE};
  mpm_nonlocal *ws = make_ws(&m, edge);
  mpm_nonlocal_implicit *im = make_im(ws);
  mpm_err err = {0};
  for (int e = 0; e < 12; e++)
    ws->lap[e] = 5.0;
  ck_assert_int_eq(mpm_nonlocal_implicit_laplacian(im, ws, 0.01, &err), MPM_EINVAL);
  ck_assert_ptr_nonnull(strstr(err.msg, "no filled unit"));
  ck_assert(ws->lap[3] == 5.0);
  for (int e = 0; e < 12; e++) {
    ws->sm[e] = 1.0;
    ws->ge[e] = 1.0;
  }
  ck_assert_int_eq(mpm_nonlocal_implicit_laplacian(im, ws, -0.01, &err), MPM_EINVAL);
  ck_assert_int_eq(mpm_nonlocal_implicit_laplacian(im, ws, NAN, &err), MPM_EINVAL);
  ck_assert_int_eq(mpm_nonlocal_implicit_laplacian(im, ws, INFINITY, &err), MPM_EINVAL);
  ck_assert(ws->lap[3] == 5.0);
  mpm_mesh m2 = make_mesh(5, 3, 0.02, 0.02, 0, 0);
  mpm_nonlocal *ws2 = make_ws(&m2, edge);
  ck_assert_int_eq(mpm_nonlocal_implicit_laplacian(im, ws2, 0.01, &err), MPM_EINVAL);
  solve(im, ws, 0.01);                       /* still usable */
  ck_assert(ws->lap[3] < 0.0);               /* g = 1 pulled down by the no-slip walls */
  mpm_linalg_stats st = mpm_nonlocal_implicit_stats(im);
  ck_assert_int_eq(st.analyses, 1);
  ck_assert_int_eq(st.factors, 1);
  mpm_nonlocal_free(ws2);
  mpm_nonlocal_implicit_free(im);
  mpm_nonlocal_implicit_free(NULL);
  mpm_nonlocal_free(ws);
}
END_TEST

int main(void)
{
  Suite *s = suite_create("implicit");
  TCase *tc = tcase_create("core");
  tcase_add_test(tc, t_periodic_cosine_decay);
  tcase_add_test(tc, t_1d_dirichlet_neumann);
  tcase_add_test(tc, t_matches_explicit_operator);
  tcase_add_test(tc, t_factor_reuse);
  tcase_add_test(tc, t_open_outlet);
  tcase_add_test(tc, t_errors);
  suite_add_tcase(s, tc);
  SRunner *sr = srunner_create(s);
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf ? EXIT_FAILURE : EXIT_SUCCESS;
}
