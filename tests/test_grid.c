/* test_grid.c: the fluidity Laplacian and its backward-Euler solve on the
 * unit grid of a mesh of either dimension (src/nonlocal/grid.c,
 * fluidity.c, implicit.c), on boxes from the equations and in the plane
 * against the plane's rules written out plainly. Tested from the equations:
 *   - a separable mode g = prod_a f_a(x_a) whose factor along each axis
 *     fits that axis's faces (periodic: cos(2 pi k x/L); Neumann at both
 *     faces: cos(pi k x/L); Dirichlet at both: sin(pi k x/L); one of each:
 *     the quarter-wave sin or cos(pi (k + 1/2) x/L); x from the first face,
 *     values at the unit centres) is an eigenvector of the discrete
 *     Laplacian, L_h g = -lambda g with lambda = sum_a 2 (1 - cos(w_a h_a))/h_a^2
 *     (w_a the mode's angular wavenumber): cos(t + s) + cos(t - s) =
 *     2 cos(t) cos(s) makes each second difference exact, and the ghosts
 *     g_e (Neumann) and -g_e (Dirichlet) are the mode's own values half a
 *     unit beyond the face, where it is even or odd. Only rounding is left:
 *     a few ulps of terms of size 4 max|g|/h^2, far below 1e-12 lambda max|g|
 *     for the modes used (lambda >= 0.05 lambda_max);
 *   - so one explicit step g + c L_h g multiplies the mode by 1 - c lambda,
 *     one implicit step (I - c L_h) g* = g divides it by 1 + c lambda and n
 *     steps by (1 + c lambda)^n (round-off: eps times the condition number
 *     1 + c lambda_max <= 61 here, so 1e-12 of max|g| holds);
 *   - an empty unit gets lap = 0 and is a Neumann face for its neighbours;
 *   - the matrix of I - c L_h (rows of mpm_nonlocal_grid_row) is symmetric
 *     entry by entry and positive definite (a dense Cholesky succeeds), its
 *     rows applied to g give g - c L_h g of the explicit stencil, and the
 *     sparse solve equals a dense solve of the same system;
 *   - the 3D stencil equals a plain reference written from the rules on
 *     random fields with every ghost kind, holes and an open face, bitwise;
 *   - in 2D the grid code gives bitwise the explicit lap_e and the implicit
 *     triplets, factor and solution of the plane's rules written out plainly
 *     (here), on random fields with every edge kind and an open outlet;
 *   - the extent rule's shares (mpm_nonlocal_grid_parts) are the overlap
 *     volumes of the box with the units over the box's volume inside the
 *     mesh, written out by hand for a box over four units, one clipped by a
 *     non-periodic face and one wrapped across a periodic one; a box inside
 *     its unit gives it 1; points with those boxes as extents, located,
 *     get those shares, and the unit sums with them (mpm_nonlocal_average)
 *     keep the dense mass and return a uniform g; a constant f is its own
 *     parts mean.
 * On boxes the faces' kinds set the ghosts: free (Neumann), no-slip
 * (Dirichlet), periodic. */
#define _DEFAULT_SOURCE /* M_PI */
#include <check.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/config.h"
#include "core/points.h"
#include "linalg/linalg.h"
#include "mesh/mesh.h"
#include "nonlocal/grid.h"
#include "nonlocal/implicit.h"
#include "nonlocal/nonlocal.h"

enum { P = MPM_GHOST_PERIODIC, N = MPM_GHOST_NEUMANN, D = MPM_GHOST_DIRICHLET };

static double lcg(unsigned long *s)
{
  *s = *s * 6364136223846793005UL + 1442695040888963407UL;
  return (double)(*s >> 11) / 9007199254740992.0;
}

/* A mesh of boxes with n[a] units of h[a] along axis a, periodic where the
 * ghost rule of its faces is. */
static mpm_mesh make_box(const int n[3], const double h[3], const int ghost[6])
{
  mpm_mesh m = {.dim = 3, .nx = n[0], .ny = n[1], .nz = n[2], .x0 = 0.3, .y0 = -0.2,
                .z0 = 1.1, .dx = h[0], .dy = h[1], .dz = h[2], .topology = MPM_TOPO_Q4,
                .periodic_x = ghost[0] == P, .periodic_y = ghost[2] == P,
                .periodic_z = ghost[4] == P};
  mpm_err err = {0};
  ck_assert_msg(mpm_mesh_setup(&m, &err) == MPM_OK, "%s", err.msg);
  return m;
}

/* The face kinds whose ghost rules are ghost[]: free (Neumann), no-slip
 * (Dirichlet), periodic. */
static void faces_of(const int ghost[6], int face[6])
{
  for (int k = 0; k < 6; k++)
    face[k] = ghost[k] == P ? MPM_BC_PERIODIC : ghost[k] == D ? MPM_BC_NOSLIP : MPM_BC_FREE;
}

/* The fluidity workspace of a mesh of boxes (centre rule) and, in *im, its
 * implicit solver. */
static mpm_nonlocal *make_ws3(const int n[3], const double h[3], const int ghost[6],
                              mpm_nonlocal_implicit **im)
{
  const mpm_mesh m = make_box(n, h, ghost);
  int face[6];
  faces_of(ghost, face);
  mpm_nonlocal *ws = NULL;
  mpm_err err = {0};
  ck_assert_msg(mpm_nonlocal_alloc(&ws, &m, face, MPM_NONLOCAL_CENTRE, 1, &err) == MPM_OK, "%s",
                err.msg);
  for (int k = 0; k < 6; k++)
    ck_assert_int_eq(ws->grid.ghost[k], ghost[k]);
  *im = mpm_nonlocal_implicit_alloc(ws, &err);
  ck_assert_msg(*im != NULL, "%s", err.msg);
  return ws;
}

static int solve3(mpm_nonlocal_implicit *im, mpm_nonlocal *ws, double c)
{
  mpm_err err = {0};
  int rc = mpm_nonlocal_implicit_laplacian(im, ws, c, &err);
  ck_assert_msg(rc == MPM_OK, "%s", err.msg);
  return rc;
}

/* ---- eigenmodes ---------------------------------------------------------- */

/* The mode's factor along one axis with faces lo, hi, wavenumber k and n
 * units of size h: its angular wavenumber *w, and whether it is a sine. */
static void axis_mode(int lo, int hi, int k, int n, double h, double *w, int *sine)
{
  const double len = n * h;
  *sine = 0;
  if (lo == P)
    *w = 2.0 * M_PI * k / len;                     /* cos(2 pi k x/L) */
  else if (lo == N && hi == N)
    *w = M_PI * k / len;                           /* cos(pi k x/L): even at both faces */
  else if (lo == D && hi == D) {
    *w = M_PI * k / len;                           /* sin(pi k x/L): odd at both */
    *sine = 1;
  } else {
    *w = M_PI * (k + 0.5) / len;                   /* quarter wave: even at N, odd at D */
    *sine = lo == D;
  }
}

typedef struct mode3 {
  double w[3];
  int sine[3];
  double lambda;          /* sum_a 2 (1 - cos(w_a h_a))/h_a^2 */
  double lambda_max;      /* sum_a 4/h_a^2 */
} mode3;

static mode3 make_mode(const int n[3], const double h[3], const int ghost[6], const int k[3])
{
  mode3 md = {.lambda = 0.0};
  for (int a = 0; a < 3; a++) {
    axis_mode(ghost[2 * a], ghost[2 * a + 1], k[a], n[a], h[a], &md.w[a], &md.sine[a]);
    md.lambda += 2.0 * (1.0 - cos(md.w[a] * h[a])) / (h[a] * h[a]);
    md.lambda_max += 4.0 / (h[a] * h[a]);
  }
  return md;
}

/* The mode at the centre of unit c (x from the first face of each axis). */
static double mode_at(const mode3 *md, const int c[3], const double h[3])
{
  double v = 1.0;
  for (int a = 0; a < 3; a++) {
    const double t = md->w[a] * (c[a] + 0.5) * h[a];
    v *= md->sine[a] ? sin(t) : cos(t);
  }
  return v;
}

/* Fill every unit of ws with g0 + amp * mode; returns max |mode|. */
static double fill_mode(mpm_nonlocal *ws, const mode3 *md, const double h[3], double g0,
                        double amp, double *f)
{
  const mpm_nonlocal_grid *g = &ws->grid;
  double mx = 0.0;
  int c[3];
  for (c[2] = 0; c[2] < g->n[2]; c[2]++)
    for (c[1] = 0; c[1] < g->n[1]; c[1]++)
      for (c[0] = 0; c[0] < g->n[0]; c[0]++) {
        const size_t e = mpm_nonlocal_grid_index(g, c);
        f[e] = mode_at(md, c, h);
        ws->sm[e] = 1.0;
        ws->ge[e] = g0 + amp * f[e];
        mx = fmax(mx, fabs(f[e]));
      }
  return mx;
}

/* The eigenmode checks on one box: explicit lap = -lambda g (and the step
 * factor 1 - c lambda), one implicit step 1/(1 + c lambda), n steps
 * (1 + c lambda)^-n, all to 1e-12 of max|g|; the factor is made once. */
static void check_mode(const int n[3], const double h[3], const int ghost[6], const int k[3],
                       const char *name)
{
  mpm_nonlocal_implicit *im = NULL;
  mpm_nonlocal *ws = make_ws3(n, h, ghost, &im);
  const mode3 md = make_mode(n, h, ghost, k);
  ck_assert_msg(md.lambda >= 0.05 * md.lambda_max, "%s: mode too smooth for the bound", name);
  const size_t nu = ws->grid.nu;
  double *f = malloc(nu * sizeof *f);
  const double fmx = fill_mode(ws, &md, h, 0.0, 1.0, f);
  /* explicit: L_h f = -lambda f, and f + c L_h f = (1 - c lambda) f */
  mpm_nonlocal_laplacian(ws);
  const double c_lim = 1.0 / (2.0 / (h[0] * h[0]) + 2.0 / (h[1] * h[1]) + 2.0 / (h[2] * h[2]));
  const double ce = 0.9 * c_lim;
  double err_lap = 0.0, err_step = 0.0;
  for (size_t e = 0; e < nu; e++) {
    err_lap = fmax(err_lap, fabs(ws->lap[e] + md.lambda * f[e]) / (md.lambda * fmx));
    err_step = fmax(err_step, fabs(f[e] + ce * ws->lap[e] - (1.0 - ce * md.lambda) * f[e]) / fmx);
  }
  /* implicit: c = 30 times the explicit limit, the mode plus a constant
   * (itself a mode, lambda = 0) when no face is Dirichlet */
  int dirichlet = 0;
  for (int q = 0; q < 6; q++)
    dirichlet |= ghost[q] == D;
  const double c = 30.0 * c_lim, g0 = dirichlet ? 0.0 : 1.5, amp = 0.8;
  const int nsteps = 5;
  fill_mode(ws, &md, h, g0, amp, f);
  double err_one = 0.0, err_n = 0.0, err_implap = 0.0;
  for (int s = 1; s <= nsteps; s++) {
    solve3(im, ws, c);
    const double *gs = mpm_nonlocal_implicit_gstar(im);
    const double a_s = amp * pow(1.0 + c * md.lambda, -s);    /* (1 + c lambda)^-s */
    for (size_t e = 0; e < nu; e++) {
      const double d = fabs(gs[e] - (g0 + a_s * f[e])) / (g0 + amp);
      if (s == 1)
        err_one = fmax(err_one, d);
      err_n = fmax(err_n, d);
      /* lap = (g* - g)/c = L_h g* = -lambda (g* - g0) */
      err_implap = fmax(err_implap, c * fabs(ws->lap[e] + md.lambda * a_s * f[e]) / (g0 + amp));
    }
    memcpy(ws->ge, gs, nu * sizeof *gs);
  }
  printf("%-34s lambda/lambda_max %.3f: |lap + lambda g| %.2g, explicit step %.2g,\n"
         "%34s implicit one step %.2g, %d steps %.2g, c |lap - L_h g*| %.2g\n", name,
         md.lambda / md.lambda_max, err_lap, err_step, "", err_one, nsteps, err_n, err_implap);
  ck_assert_msg(err_lap < 1e-12, "%s: lap error %g", name, err_lap);
  ck_assert_msg(err_step < 1e-12, "%s: explicit step error %g", name, err_step);
  ck_assert_msg(err_one < 1e-12, "%s: implicit step error %g", name, err_one);
  ck_assert_msg(err_n < 1e-12, "%s: implicit %d-step error %g", name, nsteps, err_n);
  ck_assert_msg(err_implap < 1e-12, "%s: implicit lap error %g", name, err_implap);
  mpm_linalg_stats st = mpm_nonlocal_implicit_stats(im);
  ck_assert_int_eq(st.analyses, 1);
  ck_assert_int_eq(st.factors, 1);
  ck_assert_int_eq(st.solves, nsteps);
  ck_assert_int_eq(st.fallbacks, 0);
  free(f);
  mpm_nonlocal_implicit_free(im);
  mpm_nonlocal_free(ws);
}

START_TEST(t_periodic_fourier_mode)
{
  const int n[3] = {8, 6, 10};
  const double h[3] = {0.05, 0.03, 0.04};
  const int ghost[6] = {P, P, P, P, P, P};
  check_mode(n, h, ghost, (const int[3]){1, 2, 3}, "periodic (1, 2, 3)");
  check_mode(n, h, ghost, (const int[3]){3, 0, 2}, "periodic (3, 0, 2)");
  check_mode(n, h, ghost, (const int[3]){3, 2, 4}, "periodic (3, 2, 4)");
}
END_TEST

START_TEST(t_neumann_modes)
{
  const int n[3] = {7, 5, 6};
  const double h[3] = {0.02, 0.035, 0.025};
  const int ghost[6] = {N, N, N, N, N, N};
  check_mode(n, h, ghost, (const int[3]){2, 1, 3}, "Neumann cos (2, 1, 3)");
  check_mode(n, h, ghost, (const int[3]){6, 0, 1}, "Neumann cos (6, 0, 1)");
}
END_TEST

START_TEST(t_dirichlet_modes)
{
  const int n[3] = {6, 7, 5};
  const double h[3] = {0.03, 0.02, 0.04};
  const int ghost[6] = {D, D, D, D, D, D};
  check_mode(n, h, ghost, (const int[3]){1, 1, 1}, "Dirichlet sin (1, 1, 1)");
  check_mode(n, h, ghost, (const int[3]){3, 5, 2}, "Dirichlet sin (3, 5, 2)");
}
END_TEST

START_TEST(t_mixed_faces_modes)
{
  const int n[3] = {6, 5, 8};
  const double h[3] = {0.03, 0.02, 0.025};
  /* x: Neumann / Dirichlet, y: Dirichlet / Neumann, z: periodic */
  const int ghost[6] = {N, D, D, N, P, P};
  check_mode(n, h, ghost, (const int[3]){1, 2, 2}, "N|D, D|N, periodic (1, 2, 2)");
  const int ghost2[6] = {P, P, D, D, N, N};
  check_mode(n, h, ghost2, (const int[3]){2, 3, 1}, "periodic, D|D, N|N (2, 3, 1)");
}
END_TEST

/* ---- empty units ----------------------------------------------------------- */

/* One empty unit inside a periodic box of random g: lap = 0 there, and each
 * of its six neighbours sees its own g across the face to it (Neumann),
 * written out by hand here; the implicit solve leaves it out (g* = 0 there,
 * lap = 0) and its neighbours' rows have five entries and no term for it. */
START_TEST(t_empty_unit_neumann)
{
  const int n[3] = {5, 4, 6};
  const double h[3] = {0.02, 0.03, 0.025};
  const int ghost[6] = {P, P, P, P, P, P};
  mpm_nonlocal_implicit *im = NULL;
  mpm_nonlocal *ws = make_ws3(n, h, ghost, &im);
  const mpm_nonlocal_grid *g = &ws->grid;
  unsigned long seed = 7;
  for (size_t e = 0; e < g->nu; e++) {
    ws->sm[e] = 1.0;
    ws->ge[e] = 0.5 + lcg(&seed);
  }
  const int hole[3] = {2, 1, 3};
  const size_t eh = mpm_nonlocal_grid_index(g, hole);
  ws->sm[eh] = 0.0;
  mpm_nonlocal_laplacian(ws);
  ck_assert(ws->lap[eh] == 0.0);
  double worst = 0.0;
  for (int f = 0; f < 6; f++) {                    /* the neighbour across face f of the hole */
    int c[3] = {hole[0], hole[1], hole[2]};
    const int a = f / 2;
    c[a] += f % 2 ? 1 : -1;
    const size_t e = mpm_nonlocal_grid_index(g, c);
    const double v = ws->ge[e];
    double lap = 0.0;
    for (int b = 0; b < 3; b++) {
      double side[2];
      for (int s = 0; s < 2; s++) {
        int q[3] = {c[0], c[1], c[2]};
        q[b] = (q[b] + (s ? 1 : -1) + n[b]) % n[b];
        const size_t eq = mpm_nonlocal_grid_index(g, q);
        side[s] = eq == eh ? v : ws->ge[eq];       /* the hole: g_ghost = g_e */
      }
      lap += (side[0] - 2.0 * v + side[1]) / (h[b] * h[b]);
    }
    worst = fmax(worst, fabs(ws->lap[e] - lap) / (fabs(lap) + 1.0 / (h[0] * h[0])));
    /* its row: five neighbours, the Neumann face adds nothing to the diagonal */
    size_t nb[MPM_NONLOCAL_FACES];
    double val[MPM_NONLOCAL_FACES];
    int cnt = 0;
    const double c0 = 1e-4;
    const double diag = mpm_nonlocal_grid_row(g, ws->sm, c, e, c0, nb, val, &cnt);
    ck_assert_int_eq(cnt, 5);
    double off = 0.0;
    for (int q = 0; q < cnt; q++) {
      ck_assert(nb[q] != eh);
      off -= val[q];
    }
    ck_assert_msg(fabs(diag - 1.0 - off) < 1e-14, "row %d: diag %.17g, 1 + off %.17g", f, diag,
                  1.0 + off);
    ck_assert_msg(fabs(off - c0 * (2.0 / (h[0] * h[0]) + 2.0 / (h[1] * h[1]) +
                                   2.0 / (h[2] * h[2]) - 1.0 / (h[a] * h[a]))) < 1e-12,
                  "row %d: off-diagonal sum %.17g", f, off);
  }
  printf("empty unit: neighbours' lap against the hand stencil, relative %.2g\n", worst);
  ck_assert_msg(worst < 1e-14, "empty-unit neighbour error %g", worst);
  solve3(im, ws, 1e-4);
  ck_assert(ws->lap[eh] == 0.0);
  ck_assert(mpm_nonlocal_implicit_gstar(im)[eh] == 0.0);
  mpm_nonlocal_implicit_free(im);
  mpm_nonlocal_free(ws);
}
END_TEST

/* ---- the matrix ------------------------------------------------------------- */

/* Dense matrix of I - c L_h on the filled units (rows in unit order, from
 * mpm_nonlocal_grid_row); row[e] the unit's row or -1. Returns its size. */
static int dense_matrix(const mpm_nonlocal_grid *g, const double *sm, double c, int *row,
                        double **out)
{
  int nf = 0;
  for (size_t e = 0; e < g->nu; e++)
    row[e] = sm[e] > 0.0 ? nf++ : -1;
  double *A = calloc((size_t)nf * nf, sizeof *A);
  int u[3];
  size_t e = 0;
  for (u[2] = 0; u[2] < g->n[2]; u[2]++)
    for (u[1] = 0; u[1] < g->n[1]; u[1]++)
      for (u[0] = 0; u[0] < g->n[0]; u[0]++, e++) {
        if (row[e] < 0)
          continue;
        size_t nb[MPM_NONLOCAL_FACES];
        double val[MPM_NONLOCAL_FACES];
        int cnt = 0;
        const int r = row[e];
        A[(size_t)r * nf + r] = mpm_nonlocal_grid_row(g, sm, u, e, c, nb, val, &cnt);
        for (int q = 0; q < cnt; q++) {
          ck_assert_int_ge(row[nb[q]], 0);
          A[(size_t)r * nf + row[nb[q]]] += val[q];
        }
      }
  *out = A;
  return nf;
}

/* Dense Cholesky A = L L' in place (lower triangle); 0 if a pivot is not > 0. */
static int cholesky(double *A, int n)
{
  for (int j = 0; j < n; j++) {
    double d = A[(size_t)j * n + j];
    for (int k = 0; k < j; k++)
      d -= A[(size_t)j * n + k] * A[(size_t)j * n + k];
    if (!(d > 0.0))
      return 0;
    d = sqrt(d);
    A[(size_t)j * n + j] = d;
    for (int i = j + 1; i < n; i++) {
      double s = A[(size_t)i * n + j];
      for (int k = 0; k < j; k++)
        s -= A[(size_t)i * n + k] * A[(size_t)j * n + k];
      A[(size_t)i * n + j] = s / d;
    }
  }
  return 1;
}

/* x = (L L')^-1 b. */
static void chol_solve(const double *L, int n, const double *b, double *x)
{
  for (int i = 0; i < n; i++) {
    double s = b[i];
    for (int k = 0; k < i; k++)
      s -= L[(size_t)i * n + k] * x[k];
    x[i] = s / L[(size_t)i * n + i];
  }
  for (int i = n - 1; i >= 0; i--) {
    double s = x[i];
    for (int k = i + 1; k < n; k++)
      s -= L[(size_t)k * n + i] * x[k];
    x[i] = s / L[(size_t)i * n + i];
  }
}

/* Small boxes with every face kind, holes and (second case) a periodic
 * axis of two units: the dense matrix is symmetric entry by entry and
 * positive definite, A g = g - c L_h g with the explicit stencil, and the
 * sparse solve equals the dense one to 1e-12. */
START_TEST(t_matrix_symmetric_and_dense_solve)
{
  const struct {
    int n[3];
    int ghost[6];
  } cases[] = {
    {{3, 4, 3}, {P, P, D, N, N, D}},
    {{2, 3, 4}, {P, P, N, D, D, D}},
    {{4, 2, 3}, {D, N, P, P, N, N}},
  };
  const double h[3] = {0.03, 0.02, 0.025};
  for (size_t ic = 0; ic < sizeof cases / sizeof cases[0]; ic++) {
    mpm_nonlocal_implicit *im = NULL;
    mpm_nonlocal *ws = make_ws3(cases[ic].n, h, cases[ic].ghost, &im);
    const mpm_nonlocal_grid *g = &ws->grid;
    unsigned long seed = 11 + ic;
    for (size_t e = 0; e < g->nu; e++) {
      ws->sm[e] = lcg(&seed) < 0.8 ? 1.0 : 0.0;
      ws->ge[e] = ws->sm[e] > 0.0 ? 0.2 + lcg(&seed) : 0.0;
    }
    const double c = 3e-3;                         /* c lambda_max about 60 */
    int *row = malloc(g->nu * sizeof *row);
    double *A = NULL;
    const int nf = dense_matrix(g, ws->sm, c, row, &A);
    ck_assert_int_gt(nf, 0);
    for (int i = 0; i < nf; i++)
      for (int j = 0; j < i; j++)
        ck_assert_msg(A[(size_t)i * nf + j] == A[(size_t)j * nf + i],
                      "case %zu: A[%d][%d] = %.17g, A[%d][%d] = %.17g", ic, i, j,
                      A[(size_t)i * nf + j], j, i, A[(size_t)j * nf + i]);
    /* A g = g - c L_h g: the rows and the stencil see the same ghosts */
    double *b = malloc(nf * sizeof *b), *x = malloc(nf * sizeof *x);
    mpm_nonlocal_laplacian(ws);
    double worst_op = 0.0;
    for (size_t e = 0; e < g->nu; e++) {
      if (row[e] < 0)
        continue;
      double ag = 0.0;
      for (size_t f = 0; f < g->nu; f++)
        if (row[f] >= 0)
          ag += A[(size_t)row[e] * nf + row[f]] * ws->ge[f];
      worst_op = fmax(worst_op, fabs(ag - (ws->ge[e] - c * ws->lap[e])));
    }
    double *L = malloc((size_t)nf * nf * sizeof *L);
    memcpy(L, A, (size_t)nf * nf * sizeof *L);
    ck_assert_msg(cholesky(L, nf), "case %zu: not positive definite", ic);
    for (size_t e = 0; e < g->nu; e++)
      if (row[e] >= 0)
        b[row[e]] = ws->ge[e];
    chol_solve(L, nf, b, x);
    solve3(im, ws, c);
    const double *gs = mpm_nonlocal_implicit_gstar(im);
    double worst = 0.0, gmax = 0.0;
    for (size_t e = 0; e < g->nu; e++) {
      if (row[e] < 0) {
        ck_assert(gs[e] == 0.0 && ws->lap[e] == 0.0);
        continue;
      }
      worst = fmax(worst, fabs(gs[e] - x[row[e]]));
      gmax = fmax(gmax, fabs(ws->ge[e]));
    }
    printf("matrix case %zu (%d filled units): symmetric, SPD; |A g - (g - c L_h g)| %.2g, "
           "|g* - dense| / max g %.2g\n", ic, nf, worst_op, worst / gmax);
    ck_assert_msg(worst_op < 1e-12 * gmax, "case %zu: operator error %g", ic, worst_op);
    ck_assert_msg(worst < 1e-12 * gmax, "case %zu: solve error %g", ic, worst);
    free(row);
    free(A);
    free(L);
    free(b);
    free(x);
    mpm_nonlocal_implicit_free(im);
    mpm_nonlocal_free(ws);
  }
}
END_TEST

/* ---- a plain 3D reference --------------------------------------------------- */

/* The stencil of one unit from the rules, written plainly: coordinates, a
 * switch per face kind. */
static double ref_lap3(const mpm_nonlocal_grid *g, const double *sm, const double *ge,
                       const int c[3], int open_face, const int lo[3], const int hi[3])
{
  const size_t e = mpm_nonlocal_grid_index(g, c);
  if (!(sm[e] > 0.0))
    return 0.0;
  const double v = ge[e];
  double lap = 0.0;
  for (int a = 0; a < 3; a++) {
    double nbv[2];
    for (int s = 0; s < 2; s++) {
      const int face = 2 * a + s;
      int q[3] = {c[0], c[1], c[2]};
      q[a] += s ? 1 : -1;
      if (q[a] < 0 || q[a] >= g->n[a]) {
        int open = face == open_face;
        for (int b = 0; b < 3; b++)
          if (b != a && (c[b] < lo[b] || c[b] >= hi[b]))
            open = 0;
        if (open || g->ghost[face] == N) {
          nbv[s] = v;
          continue;
        }
        if (g->ghost[face] == D) {
          nbv[s] = -v;
          continue;
        }
        q[a] = (q[a] + g->n[a]) % g->n[a];
      }
      const size_t eq = mpm_nonlocal_grid_index(g, q);
      nbv[s] = sm[eq] > 0.0 ? ge[eq] : v;
    }
    const double t = (nbv[1] - 2.0 * v + nbv[0]) * g->ih2[a];
    lap = a == 0 ? t : lap + t;
  }
  return lap;
}

START_TEST(t_reference_3d_random)
{
  const int kinds[3] = {N, D, P};
  const double h[3] = {0.02, 0.03, 0.025};
  unsigned long seed = 3;
  int ncases = 0;
  for (int kx = 0; kx < 3; kx++)
    for (int ky = 0; ky < 3; ky++)
      for (int kz = 0; kz < 3; kz++) {
        /* non-periodic axes take the two non-periodic kinds in turn */
        int ghost[6] = {kinds[kx], kinds[kx], kinds[ky], kinds[ky], kinds[kz], kinds[kz]};
        if (kinds[kx] != P)
          ghost[1] = kinds[(kx + 1) % 2];
        if (kinds[kz] != P)
          ghost[4] = kinds[(kz + 1) % 2];
        const int n[3] = {4 + kx, 3 + ky, 5 - kz};
        mpm_nonlocal_implicit *im = NULL;
        mpm_nonlocal *ws = make_ws3(n, h, ghost, &im);
        mpm_nonlocal_grid *g = &ws->grid;
        for (size_t e = 0; e < g->nu; e++) {
          ws->sm[e] = lcg(&seed) < 0.75 ? lcg(&seed) : 0.0;
          ws->ge[e] = lcg(&seed) - 0.3;
        }
        int open_face = -1, lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
        if (ghost[2] != P) {                       /* an outlet on the -y face */
          open_face = 2;
          lo[0] = 1;
          hi[0] = n[0] - 1;
          lo[2] = 1;
          hi[2] = n[2];
          mpm_nonlocal_grid_open_faces(g, open_face, lo, hi);
        }
        mpm_nonlocal_laplacian(ws);
        int c[3];
        for (c[2] = 0; c[2] < n[2]; c[2]++)
          for (c[1] = 0; c[1] < n[1]; c[1]++)
            for (c[0] = 0; c[0] < n[0]; c[0]++) {
              const double r = ref_lap3(g, ws->sm, ws->ge, c, open_face, lo, hi);
              const double l = ws->lap[mpm_nonlocal_grid_index(g, c)];
              ck_assert_msg(memcmp(&r, &l, sizeof r) == 0,
                            "ghosts %d%d%d%d%d%d unit (%d, %d, %d): %.17g, reference %.17g",
                            ghost[0], ghost[1], ghost[2], ghost[3], ghost[4], ghost[5], c[0],
                            c[1], c[2], l, r);
            }
        mpm_nonlocal_implicit_free(im);
        mpm_nonlocal_free(ws);
        ncases++;
      }
  printf("3D stencil = plain reference bitwise on %d boxes (every face kind, holes, outlets)\n",
         ncases);
}
END_TEST

/* ---- 2D: the grid code against the plane's rules written out ------------------ */

/* The plane's side rule, Laplacian and implicit assembly written out on
 * plain arrays: four sides W, E, S, N, a ghost rule per edge, an open
 * stretch of one edge, the lower triangle of I - c L_h row by row. */
typedef struct plain2d {
  int nx, ny;
  double idx2, idy2;
  int ghost[4];
  int open_edge, open_lo, open_hi;
  const double *sm, *ge;
} plain2d;

static const int plain_di[4] = {-1, 1, 0, 0}, plain_dj[4] = {0, 0, -1, 1};

static int plain_side(const plain2d *ws, int i, int j, int side, size_t *nb)
{
  int ii = i + plain_di[side], jj = j + plain_dj[side], edge = -1;
  if (ii < 0)
    edge = 0;
  else if (ii >= ws->nx)
    edge = 1;
  else if (jj < 0)
    edge = 2;
  else if (jj >= ws->ny)
    edge = 3;
  if (edge >= 0) {
    const int along = edge <= 1 ? j : i;
    if (edge == ws->open_edge && along >= ws->open_lo && along < ws->open_hi)
      return 1;
    if (ws->ghost[edge] == MPM_GHOST_DIRICHLET)
      return -1;
    if (ws->ghost[edge] == MPM_GHOST_NEUMANN)
      return 1;
    ii = (ii + ws->nx) % ws->nx;
    jj = (jj + ws->ny) % ws->ny;
  }
  size_t e = (size_t)ii + (size_t)ws->nx * (size_t)jj;
  if (!(ws->sm[e] > 0.0))
    return 1;
  *nb = e;
  return 0;
}

static double plain_neighbour(const plain2d *ws, int i, int j, int side, double g)
{
  size_t nb = 0;
  int k = plain_side(ws, i, j, side, &nb);
  return k == 0 ? ws->ge[nb] : k * g;
}

static void plain_laplacian(const plain2d *ws, double *lapv)
{
  for (int j = 0; j < ws->ny; j++)
    for (int i = 0; i < ws->nx; i++) {
      size_t e = (size_t)i + (size_t)ws->nx * (size_t)j;
      if (!(ws->sm[e] > 0.0)) {
        lapv[e] = 0.0;
        continue;
      }
      double g = ws->ge[e];
      double gw = plain_neighbour(ws, i, j, 0, g), ge = plain_neighbour(ws, i, j, 1, g);
      double gs = plain_neighbour(ws, i, j, 2, g), gn = plain_neighbour(ws, i, j, 3, g);
      lapv[e] = (ge - 2.0 * g + gw) * ws->idx2 + (gn - 2.0 * g + gs) * ws->idy2;
    }
}

static size_t plain_assemble(const plain2d *ws, const int *row, double c, int *ti, int *tj,
                           double *tv)
{
  size_t k = 0;
  for (int j = 0; j < ws->ny; j++)
    for (int i = 0; i < ws->nx; i++) {
      const size_t e = (size_t)i + (size_t)ws->nx * (size_t)j;
      const int r = row[e];
      if (r < 0)
        continue;
      double diag = 1.0;
      for (int s = 0; s < 4; s++) {
        const double cw = c * (s <= 1 ? ws->idx2 : ws->idy2);
        size_t nb = 0;
        const int kg = plain_side(ws, i, j, s, &nb);
        if (kg != 0) {
          diag += (1 - kg) * cw;
          continue;
        }
        const int rn = row[nb];
        if (rn == r)
          continue;
        diag += cw;
        if (rn < r) {
          ti[k] = r;
          tj[k] = rn;
          tv[k++] = -cw;
        }
      }
      ti[k] = r;
      tj[k] = r;
      tv[k++] = diag;
    }
  return k;
}

/* Random 2D workspaces with every edge kind (each axis periodic, or two of
 * free, no-slip, frictionless, symmetry), holes and an open outlet: lap_e of
 * mpm_nonlocal_laplacian, of the grid code called directly, and the
 * implicit solution are bitwise those of the rules written out above (their
 * triplets solved through the same linalg calls). */
START_TEST(t_2d_bitwise_plain_rules)
{
  const int kinds[4] = {MPM_BC_FREE, MPM_BC_NOSLIP, MPM_BC_FRICTIONLESS, MPM_BC_SYMMETRY};
  unsigned long seed = 5;
  int ncases = 0;
  for (int trial = 0; trial < 40; trial++) {
    const int px = trial % 4 == 1, py = trial % 4 == 2 || trial % 8 == 3;
    int edge[4];
    for (int k = 0; k < 4; k++)
      edge[k] = kinds[(int)(4.0 * lcg(&seed)) % 4];
    if (px)
      edge[0] = edge[1] = MPM_BC_PERIODIC;
    if (py)
      edge[2] = edge[3] = MPM_BC_PERIODIC;
    const int nx = 2 + (int)(9.0 * lcg(&seed)), ny = 2 + (int)(7.0 * lcg(&seed));
    mpm_mesh m = {.nx = nx, .ny = ny, .x0 = 0.1, .y0 = 0.0, .dx = 0.013 + 0.02 * lcg(&seed),
                  .dy = 0.011 + 0.02 * lcg(&seed), .topology = MPM_TOPO_Q4, .periodic_x = px,
                  .periodic_y = py};
    mpm_err err = {0};
    ck_assert_int_eq(mpm_mesh_setup(&m, &err), MPM_OK);
    mpm_nonlocal *ws = NULL;
    ck_assert_int_eq(mpm_nonlocal_alloc(&ws, &m, edge, MPM_NONLOCAL_CENTRE, 4, &err), MPM_OK);
    if (trial % 5 == 4)
      mpm_nonlocal_walls_neumann(ws);
    const size_t nu = (size_t)nx * ny;
    for (size_t e = 0; e < nu; e++) {
      ws->sm[e] = lcg(&seed) < 0.8 ? 0.1 + lcg(&seed) : 0.0;
      ws->ge[e] = ws->sm[e] > 0.0 ? lcg(&seed) : 0.0;
    }
    plain2d pl = {.nx = nx, .ny = ny, .idx2 = 1.0 / (m.dx * m.dx), .idy2 = 1.0 / (m.dy * m.dy),
                 .open_edge = -1, .sm = ws->sm, .ge = ws->ge};
    for (int k = 0; k < 4; k++) {
      pl.ghost[k] = mpm_nonlocal_ghost_of_bc(edge[k]);
      if (trial % 5 == 4 && pl.ghost[k] == MPM_GHOST_DIRICHLET)
        pl.ghost[k] = MPM_GHOST_NEUMANN;
    }
    if (trial % 3 != 0) {                          /* an outlet on a non-periodic edge */
      const int oe = !py ? 2 + trial % 2 : trial % 2;
      if (!(oe <= 1 ? px : py)) {
        const int len = oe <= 1 ? ny : nx;
        const int lo = (int)(len * lcg(&seed)), hi = lo + 1 + (int)((len - lo) * lcg(&seed));
        int lo3[3] = {0, 0, 0}, hi3[3] = {0, 0, 0};
        lo3[oe <= 1 ? 1 : 0] = lo;
        hi3[oe <= 1 ? 1 : 0] = hi;
        ck_assert_int_eq(mpm_nonlocal_open_faces(ws, oe, lo3, hi3, NULL, &err), MPM_OK);
        pl.open_edge = oe;
        pl.open_lo = lo;
        pl.open_hi = hi;
      }
    }
    double *ref = malloc(nu * sizeof *ref), *lap2 = malloc(nu * sizeof *lap2);
    plain_laplacian(&pl, ref);
    mpm_nonlocal_laplacian(ws);
    ck_assert_msg(memcmp(ref, ws->lap, nu * sizeof *ref) == 0, "trial %d: explicit lap differs",
                  trial);
    mpm_nonlocal_grid_laplacian(&ws->grid, ws->sm, ws->ge, lap2);
    ck_assert_msg(memcmp(ref, lap2, nu * sizeof *ref) == 0, "trial %d: grid lap differs", trial);
    /* the sides one by one */
    for (int j = 0; j < ny; j++)
      for (int i = 0; i < nx; i++)
        for (int s = 0; s < 4; s++) {
          size_t a = 7, b = 7;
          const int c[3] = {i, j, 0};
          ck_assert_int_eq(mpm_nonlocal_grid_side(&ws->grid, ws->sm, c, (size_t)i + (size_t)nx * j,
                                                  s, &a),
                           plain_side(&pl, i, j, s, &b));
          ck_assert(a == b);
        }
    /* implicit: the plain triplets through linalg against the 2D implicit solve */
    int *row = malloc(nu * sizeof *row);
    int nf = 0;
    for (size_t e = 0; e < nu; e++)
      row[e] = ws->sm[e] > 0.0 ? nf++ : -1;
    if (nf > 0) {
      const double c = (0.5 + 50.0 * lcg(&seed)) / (2.0 * pl.idx2 + 2.0 * pl.idy2);
      int *ti = malloc(5 * nu * sizeof *ti), *tj = malloc(5 * nu * sizeof *tj);
      double *tv = malloc(5 * nu * sizeof *tv), *b = malloc(nu * sizeof *b);
      double *x = malloc(nu * sizeof *x);
      const size_t nt = plain_assemble(&pl, row, c, ti, tj, tv);
      mpm_linalg_spd *spd = mpm_linalg_spd_alloc(&err);
      ck_assert(spd != NULL);
      ck_assert_int_eq(mpm_linalg_spd_set(spd, nf, nt, ti, tj, tv, &err), MPM_OK);
      ck_assert_int_eq(mpm_linalg_spd_analyse(spd, &err), MPM_OK);
      ck_assert_int_eq(mpm_linalg_spd_factor(spd, &err), MPM_OK);
      for (size_t e = 0; e < nu; e++)
        if (row[e] >= 0)
          b[row[e]] = ws->ge[e];
      ck_assert_int_eq(mpm_linalg_spd_solve(spd, b, x, &err), MPM_OK);
      for (size_t e = 0; e < nu; e++)
        ref[e] = row[e] >= 0 ? (x[row[e]] - ws->ge[e]) / c : 0.0;
      mpm_nonlocal_implicit *im = mpm_nonlocal_implicit_alloc(ws, &err);
      ck_assert(im != NULL);
      ck_assert_msg(mpm_nonlocal_implicit_laplacian(im, ws, c, &err) == MPM_OK, "%s", err.msg);
      ck_assert_msg(memcmp(ref, ws->lap, nu * sizeof *ref) == 0,
                    "trial %d: implicit lap differs", trial);
      /* the grid rows are the plain rows: diagonal and entries, bitwise */
      int u[3] = {0, 0, 0};
      size_t k = 0;
      for (u[1] = 0; u[1] < ny; u[1]++)
        for (u[0] = 0; u[0] < nx; u[0]++) {
          const size_t e = (size_t)u[0] + (size_t)nx * u[1];
          if (row[e] < 0)
            continue;
          size_t nb[MPM_NONLOCAL_FACES];
          double val[MPM_NONLOCAL_FACES];
          int cnt = 0;
          const double diag = mpm_nonlocal_grid_row(&ws->grid, ws->sm, u, e, c, nb, val, &cnt);
          for (int q = 0; q < cnt; q++)
            if (row[nb[q]] < row[e]) {
              ck_assert(ti[k] == row[e] && tj[k] == row[nb[q]]);
              ck_assert(memcmp(&tv[k], &val[q], sizeof val[q]) == 0);
              k++;
            }
          ck_assert(ti[k] == row[e] && tj[k] == row[e]);
          ck_assert(memcmp(&tv[k], &diag, sizeof diag) == 0);
          k++;
        }
      ck_assert(k == nt);
      mpm_nonlocal_implicit_free(im);
      mpm_linalg_spd_free(spd);
      free(ti);
      free(tj);
      free(tv);
      free(b);
      free(x);
    }
    free(row);
    free(ref);
    free(lap2);
    mpm_nonlocal_free(ws);
    ncases++;
  }
  printf("2D grid code = the plane's rules written out, bitwise, on %d random workspaces\n",
         ncases);
}
END_TEST

/* ---- extent rule ------------------------------------------------------------ */

/* Boxes of half-width 0.25 unit on a 4 x 4 x 4 grid, faces -x, +x Neumann,
 * -y, +y Dirichlet, -z, +z periodic (x fastest in the slots, then y, z):
 *  (a) centre (0.9, 0.1, 0.5) of unit (1, 1, 1): along x 0.35 in unit 1 and
 *      0.15 in 2, along y 0.35 in 1 and 0.15 in 0, along z all in 1; shares
 *      0.35^2, 0.15 0.35, 0.35 0.15, 0.15^2 over 0.25 = 0.49, 0.21, 0.21,
 *      0.09;
 *  (b) centre (0.1, 0.5, 0.5) of unit (0, 2, 2): x's part in unit -1 is
 *      beyond a non-periodic face: unit (0, 2, 2) alone, share 1;
 *  (c) centre (0.5, 0.5, 0.1) of unit (2, 2, 0): z's part wraps to unit 3,
 *      0.35 / 0.5 and 0.15 / 0.5 = 0.7, 0.3;
 *  (d) centre (0.5, 0.5, 0.5), half-widths 0.5: inside, share 1. */
START_TEST(t_extent_parts)
{
  const int n[3] = {4, 4, 4};
  const double h[3] = {0.1, 0.2, 0.3};
  const int ghost[6] = {N, N, D, D, P, P};
  const mpm_mesh m = make_box(n, h, ghost);
  int face[6];
  faces_of(ghost, face);
  mpm_nonlocal *ws = NULL;
  mpm_err err = {0};
  ck_assert_int_eq(mpm_nonlocal_alloc(&ws, &m, face, MPM_NONLOCAL_EXTENT, 4, &err), MPM_OK);
  ck_assert_int_eq(ws->nparts, MPM_NONLOCAL_PARTS);
  const mpm_nonlocal_grid *g = &ws->grid;
  /* the shares by hand (mpm_nonlocal_grid_parts from a unit and a local
   * position) */
  struct { int c[3]; double u[3], hw; int nz; int unit[4][3]; double w[4]; } cs[4] = {
    {{1, 1, 1}, {0.9, 0.1, 0.5}, 0.25, 4,
     {{1, 1, 1}, {2, 1, 1}, {1, 0, 1}, {2, 0, 1}}, {0.49, 0.21, 0.21, 0.09}},
    {{0, 2, 2}, {0.1, 0.5, 0.5}, 0.25, 1, {{0, 2, 2}}, {1.0}},
    {{2, 2, 0}, {0.5, 0.5, 0.1}, 0.25, 2, {{2, 2, 0}, {2, 2, 3}}, {0.7, 0.3}},
    {{3, 0, 3}, {0.5, 0.5, 0.5}, 0.5, 1, {{3, 0, 3}}, {1.0}},
  };
  for (int t = 0; t < 4; t++) {
    int part[MPM_NONLOCAL_PARTS];
    double w[MPM_NONLOCAL_PARTS];
    const double hw[3] = {cs[t].hw, cs[t].hw, cs[t].hw};
    mpm_nonlocal_grid_parts(g, cs[t].c, cs[t].u, hw, part, w);
    double sum = 0.0;
    for (int k = 0; k < MPM_NONLOCAL_PARTS; k++) {
      if (k < cs[t].nz) {
        ck_assert_int_eq(part[k], (int)mpm_nonlocal_grid_index(g, cs[t].unit[k]));
        ck_assert_double_eq_tol(w[k], cs[t].w[k], 1e-15);
      } else {
        ck_assert_int_eq(part[k], (int)mpm_nonlocal_grid_index(g, cs[t].c));
        ck_assert(w[k] == 0.0);
      }
      sum += w[k];
    }
    ck_assert_double_eq_tol(sum, 1.0, 1e-15);
  }
  mpm_nonlocal_free(ws);
  /* unit sums: 3 dense points of masses 1, 2, 4 and g 5 (and one not dense,
   * g 99) whose extents are boxes like (a), (c), (d) (and (b)), located
   * (mpm_nonlocal_locate: the half-widths sum_k |r_ka| in units, the local
   * position of the centre) on a mesh whose origin and unit sizes are
   * binary fractions, at positions that are too (u = 1/8 or 7/8 instead of
   * 0.1, 0.9): the shares are then exact, 3/4 and 1/4 along an axis the box
   * crosses (a: 9/16, 3/16, 3/16, 1/16; c: 3/4, 1/4) */
  const double hb[3] = {0.125, 0.25, 0.5};
  mpm_mesh mb = make_box(n, hb, ghost);
  mb.x0 = mb.y0 = mb.z0 = 0.0;
  ck_assert_int_eq(mpm_mesh_setup(&mb, &err), MPM_OK);
  ck_assert_int_eq(mpm_nonlocal_alloc(&ws, &mb, face, MPM_NONLOCAL_EXTENT, 4, &err), MPM_OK);
  g = &ws->grid;
  struct { int c[3]; double u[3], hw; int nz; int unit[4][3]; double w[4]; } bs[4] = {
    {{1, 1, 1}, {0.875, 0.125, 0.5}, 0.25, 4,
     {{1, 1, 1}, {2, 1, 1}, {1, 0, 1}, {2, 0, 1}}, {0.5625, 0.1875, 0.1875, 0.0625}},
    {{0, 2, 2}, {0.125, 0.5, 0.5}, 0.25, 1, {{0, 2, 2}}, {1.0}},
    {{2, 2, 0}, {0.5, 0.5, 0.125}, 0.25, 2, {{2, 2, 0}, {2, 2, 3}}, {0.75, 0.25}},
    {{3, 0, 3}, {0.5, 0.5, 0.5}, 0.5, 1, {{3, 0, 3}}, {1.0}},
  };
  const double mass[4] = {1.0, 2.0, 4.0, 8.0}, gp[4] = {5.0, 5.0, 5.0, 99.0};
  const unsigned char dense[4] = {1, 1, 1, 0};
  const int use[4] = {0, 2, 3, 1};
  mpm_points *pts = mpm_points_alloc_dim(4, 3);
  for (int p = 0; p < 4; p++) {
    size_t i;
    ck_assert_int_eq(mpm_points_push(pts, &i), MPM_OK);
    for (int d = 0; d < 3; d++) {
      pts->pos[d][i] = (bs[use[p]].c[d] + bs[use[p]].u[d]) * mb.h[d];
      pts->ext[d][d][i] = (p % 2 ? -1.0 : 1.0) * bs[use[p]].hw * mb.h[d];   /* either sign */
    }
  }
  ck_assert_msg(mpm_nonlocal_locate(ws, &mb, pts, &err) == MPM_OK, "%s", err.msg);
  for (int p = 0; p < 4; p++) {
    const int t = use[p];
    double sum = 0.0;
    for (int k = 0; k < bs[t].nz; k++) {
      double w = 0.0;                                /* the weight of that unit */
      const int e = (int)mpm_nonlocal_grid_index(g, bs[t].unit[k]);
      for (int q = 0; q < ws->nparts; q++)
        w += ws->part[ws->nparts * p + q] == e ? ws->w[ws->nparts * p + q] : 0.0;
      ck_assert_double_eq_tol(w, bs[t].w[k], 1e-15);
      sum += w;
    }
    ck_assert_double_eq_tol(sum, 1.0, 1e-15);        /* no other unit has a share */
  }
  mpm_nonlocal_average(ws, 4, mass, gp, dense);
  double total = 0.0;
  int filled = 0;
  for (size_t e = 0; e < g->nu; e++) {
    total += ws->sm[e];
    if (ws->sm[e] > 0.0) {
      filled++;
      ck_assert_double_eq_tol(ws->ge[e], 5.0, 1e-14);
    } else
      ck_assert(ws->ge[e] == 0.0);
  }
  ck_assert_double_eq_tol(total, 7.0, 1e-15);
  ck_assert_int_eq(filled, 4 + 2 + 1);
  const int u0[3] = {2, 1, 1};
  ck_assert_double_eq_tol(ws->sm[mpm_nonlocal_grid_index(g, u0)], 0.1875, 1e-15);
  /* a constant field is its own mean over the filled parts */
  double f[64];
  for (int e = 0; e < 64; e++)
    f[e] = 3.5;
  for (int p = 0; p < 3; p++)                      /* the dense points' units are filled */
    ck_assert_double_eq_tol(mpm_nonlocal_point_mean(ws, f, (size_t)p), 3.5, 1e-15);
  ck_assert_double_eq_tol(mpm_nonlocal_grid_parts_mean(ws->sm, f, ws->part, ws->w,
                                                       MPM_NONLOCAL_PARTS), 3.5, 1e-15);
  mpm_points_free(pts);
  mpm_nonlocal_free(ws);
}
END_TEST

/* ---- errors ------------------------------------------------------------------ */

START_TEST(t_errors)
{
  const int n[3] = {3, 3, 3};
  const double h[3] = {0.1, 0.1, 0.1};
  const int ghost[6] = {N, N, D, D, P, P};
  const mpm_mesh m = make_box(n, h, ghost);
  mpm_nonlocal *ws = NULL;
  mpm_err err = {0};
  int face[6];
  const int bad_pair[6] = {N, N, D, D, P, N};
  faces_of(bad_pair, face);
  ck_assert_int_eq(mpm_nonlocal_alloc(&ws, &m, face, MPM_NONLOCAL_CENTRE, 1, &err), MPM_EINVAL);
  ck_assert(ws == NULL);
  const int not_mesh[6] = {P, P, D, D, P, P};
  faces_of(not_mesh, face);
  ck_assert_int_eq(mpm_nonlocal_alloc(&ws, &m, face, MPM_NONLOCAL_CENTRE, 1, &err), MPM_EINVAL);
  faces_of(ghost, face);
  face[1] = 7;                                     /* an unknown kind */
  ck_assert_int_eq(mpm_nonlocal_alloc(&ws, &m, face, MPM_NONLOCAL_CENTRE, 1, &err), MPM_EINVAL);
  ck_assert_msg(strstr(err.msg, "face +x") != NULL, "%s", err.msg);
  faces_of(ghost, face);
  ck_assert_int_eq(mpm_nonlocal_alloc(&ws, &m, face, MPM_NONLOCAL_CENTRE, 1, &err), MPM_OK);
  mpm_nonlocal_implicit *im = mpm_nonlocal_implicit_alloc(ws, &err);
  ck_assert(im != NULL);
  for (size_t e = 0; e < ws->grid.nu; e++)        /* no solve yet: g* = 0 */
    ck_assert(mpm_nonlocal_implicit_gstar(im)[e] == 0.0);
  err = (mpm_err){0};
  ck_assert_int_eq(mpm_nonlocal_implicit_laplacian(im, ws, 1e-3, &err), MPM_EINVAL);  /* no filled unit */
  ws->sm[0] = 1.0;
  ck_assert_int_eq(mpm_nonlocal_implicit_laplacian(im, ws, -1.0, &err), MPM_EINVAL);
  ck_assert_int_eq(mpm_nonlocal_implicit_laplacian(im, ws, NAN, &err), MPM_EINVAL);
  mpm_nonlocal_implicit_free(im);
  /* a solver made for another grid */
  mpm_nonlocal_grid g2 = {0};
  const int n2[2] = {3, 9};
  ck_assert_int_eq(mpm_nonlocal_grid_set(&g2, 2, n2, h, ghost, &err), MPM_OK);
  im = mpm_nonlocal_implicit_alloc_grid(&g2, &err);
  ck_assert(im != NULL);
  ck_assert_int_eq(mpm_nonlocal_implicit_grid(im, &ws->grid, ws->sm, ws->ge, ws->lap, 1e-3,
                                              &err), MPM_EINVAL);
  printf("error: %s\n", err.msg);
  mpm_nonlocal_implicit_free(im);
  ck_assert_int_eq(mpm_nonlocal_grid_set(&g2, 4, n2, h, ghost, &err), MPM_EINVAL);
  mpm_nonlocal_free(ws);
  mpm_nonlocal_free(NULL);
  mpm_nonlocal_implicit_free(NULL);
}
END_TEST

int main(void)
{
  Suite *s = suite_create("grid");
  TCase *tc = tcase_create("grid");
  tcase_add_test(tc, t_periodic_fourier_mode);
  tcase_add_test(tc, t_neumann_modes);
  tcase_add_test(tc, t_dirichlet_modes);
  tcase_add_test(tc, t_mixed_faces_modes);
  tcase_add_test(tc, t_empty_unit_neumann);
  tcase_add_test(tc, t_matrix_symmetric_and_dense_solve);
  tcase_add_test(tc, t_reference_3d_random);
  tcase_add_test(tc, t_2d_bitwise_plain_rules);
  tcase_add_test(tc, t_errors);
  tcase_add_test(tc, t_extent_parts);
  suite_add_tcase(s, tc);
  SRunner *sr = srunner_create(s);
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf ? EXIT_FAILURE : EXIT_SUCCESS;
}
