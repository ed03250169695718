/* v9.c: V9, the Galerkin solve of the steady fluidity ([D-thesis] section
 * 3.5.2, MODEL.md section 6) on a frozen point cloud, without the MPM step.
 *
 * The stress of the vertical chute ([D-thesis] ch. 4 and App. A, the
 * parameters of inputs/vertical-chute.conf): walls at x = 0 and L, periodic in
 * y, uniform p, tau = rho grav |x - L/2| (the wall shear carries the weight),
 * set on n x n points per unit of an nx x ny Q4 mesh with delta weights;
 * granmpm's steady field (mpm_nonlocal_steady_field, model ngf, form hs21)
 * gives the nodal g.
 *  1. Against the 1D reference (verification/ngf1d vchute --equation kk, read
 *     from the files given): relative L2 error of the nodal g over the nodes of
 *     one row and its observed order under refinement, for zero flux at the
 *     walls ([D-thesis] App. A.2) and g = 0 there, consistent and lumped w S S
 *     (one point per unit: the consistent matrix is singular, MODEL.md
 *     section 6; its order is erratic, as the cell that holds mu = mu_s
 *     changes, and is not a target).
 *  2. Against an independent dense solve: the matrix and right-hand side of
 *     MODEL.md section 6 assembled here from the point positions with the
 *     bilinear basis written out by hand, solved by Gaussian elimination with
 *     partial pivoting; granmpm's nodal g must agree to 1e-10 (relative), with
 *     Cholesky (the symmetric positive definite system) and, after making the
 *     system indefinite on purpose (w = 1/xi^2 negated on the points with
 *     x < L/4), through the QR fallback, which the solver statistics must show.
 * Prints "name measured target PASS|FAIL" lines; exit status 0 if all pass.
 *
 *   v9 REF_NEUMANN REF_DIRICHLET [--quick]
 * REF_*: CSV of `ngf1d vchute --equation kk --b 18.754 --grav 0.8 --wall ...`. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/config.h"
#include "core/points.h"
#include "material/material.h"
#include "mesh/mesh.h"
#include "nonlocal/field.h"
#include "nonlocal/nonlocal.h"
#include "nonlocal/steady.h"
#include "shape/shape.h"

/* [D-thesis] Table 4.1 and the gravity of V8 (README). */
#define L_W 1.0        /* width [m] */
#define P0 900.0       /* pressure [Pa] */
#define RHO 1500.0     /* bulk density [kg/m^3] */
#define GRAV 0.8       /* gravity [m/s^2] */
#define A_NL 0.48
#define D_G 0.05       /* grain diameter [m] */
#define B_LIN 18.754   /* b of mu = mu_s + b I */
#define MU_S 0.3819
#define RHO_S 2450.0

typedef struct tally { int fails; } tally;

static void report(tally *t, const char *name, double v, double lo, double hi)
{
  const int ok = v >= lo && v <= hi;
  printf("%-66s %11.4g  in [%g, %g]  %s\n", name, v, lo, hi, ok ? "PASS" : "FAIL");
  t->fails += !ok;
}

/* ---- the reference ------------------------------------------------------- */

typedef struct ref { int n; double *x, *g; } ref;

static int read_ref(const char *path, ref *r)
{
  FILE *f = fopen(path, "r");
  if (!f)
    return -1;
  char line[512];
  size_t cap = 1024;
  r->n = 0;
  r->x = malloc(cap * sizeof(double));
  r->g = malloc(cap * sizeof(double));
  while (fgets(line, sizeof line, f)) {
    double x, g;
    if (line[0] == '#' || sscanf(line, "%lf,%lf", &x, &g) != 2)
      continue;
    if ((size_t)r->n == cap) {
      cap *= 2;
      r->x = realloc(r->x, cap * sizeof(double));
      r->g = realloc(r->g, cap * sizeof(double));
    }
    r->x[r->n] = x + 0.5 * L_W;                          /* ngf1d: x from -L/2 */
    r->g[r->n++] = g;
  }
  fclose(f);
  return r->n > 1 ? 0 : -1;
}

static double ref_at(const ref *r, double x)
{
  int k = 0;
  while (k < r->n - 2 && r->x[k + 1] < x)
    k++;
  double s = (x - r->x[k]) / (r->x[k + 1] - r->x[k]);
  return r->g[k] + s * (r->g[k + 1] - r->g[k]);
}

/* ---- the point cloud ----------------------------------------------------- */

typedef struct cloud {
  mpm_mesh m;
  mpm_points *P;
  mpm_shape_stencil *st;
  mpm_material_params par;
} cloud;

static int make_cloud(cloud *c, int nx, int n)
{
  const int ny = 4;
  const double dx = L_W / nx;
  c->m = (mpm_mesh){.nx = nx, .ny = ny, .dx = dx, .dy = dx, .topology = MPM_TOPO_Q4,
                    .periodic_y = 1};
  mpm_err err = {0};
  if (mpm_mesh_setup(&c->m, &err) != MPM_OK)
    return -1;
  c->P = mpm_points_alloc(1024);
  for (int j = 0; j < ny * n; j++)
    for (int i = 0; i < nx * n; i++) {
      size_t p;
      mpm_points_push(c->P, &p);
      const double x = (i + 0.5) * dx / n, y = (j + 0.5) * dx / n;
      c->P->x[p] = x;
      c->P->y[p] = y;
      c->P->vol[p] = dx * dx / (n * n);
      c->P->mass[p] = RHO * c->P->vol[p];
      c->P->sxx[p] = c->P->syy[p] = c->P->szz[p] = -P0;
      c->P->sxy[p] = -RHO * GRAV * (x - 0.5 * L_W);        /* tau = rho grav |x - L/2| */
      c->P->state[p] = MPM_STATE_DENSE;
    }
  c->st = mpm_shape_stencil_alloc(c->P->n);
  if (mpm_shape_stencil_compute(c->st, &mpm_shape_delta, &c->m, c->P, 0.0, &err) != MPM_OK)
    return -1;
  mpm_config cfg = {0};
  mpm_material_config_dk15(&cfg);
  cfg.material.E = 1e8;
  cfg.material.rho_s = RHO_S;
  cfg.material.mu_s = MU_S;
  cfg.material.I0 = 0.279;
  cfg.material.mu_2 = MU_S + B_LIN * 0.279;              /* b = (mu_2 - mu_s)/I0 */
  cfg.material.d = D_G;
  cfg.material.A = A_NL;
  cfg.material.t0 = 1e-3;
  cfg.material.form = MPM_NGF_HS21;
  mpm_material_params_from_config(&c->par, &cfg);
  return 0;
}

static void free_cloud(cloud *c)
{
  mpm_shape_stencil_free(c->st);
  mpm_points_free(c->P);
}

/* The steady field through granmpm (model ngf, form hs21, element rule):
 * the nodal g copied to g[m.nnodes]; wall: enum mpm_nonlocal_wall. Returns 0
 * or -1 (message printed). */
static int granmpm_field(cloud *c, int wall, int mass, double *g, mpm_linalg_stats *s)
{
  const int edge[4] = {MPM_BC_NOSLIP, MPM_BC_NOSLIP, MPM_BC_PERIODIC, MPM_BC_PERIODIC};
  mpm_nonlocal *ws = NULL;
  mpm_err err = {0};
  int rc = mpm_nonlocal_alloc(&ws, &c->m, edge, MPM_NONLOCAL_CENTRE, c->P->n, &err);
  if (rc == MPM_OK)
    rc = mpm_nonlocal_set_diffusion(ws, MPM_DIFFUSION_STEADY, &err);
  if (rc == MPM_OK && wall == MPM_NONLOCAL_WALL_NEUMANN)
    mpm_nonlocal_walls_neumann(ws);
  if (rc == MPM_OK)
    rc = mpm_nonlocal_steady_field(ws, &mpm_material_ngf, &c->par, c->P, c->st, &c->m,
                                   MPM_STEADY_ELEMENT, mass, &err);
  const double *gn = rc == MPM_OK ? mpm_nonlocal_steady_field_nodal(ws) : NULL;
  if (rc != MPM_OK || !gn) {
    printf("  granmpm: %s\n", rc != MPM_OK ? err.msg : "no nodal field");
    mpm_nonlocal_free(ws);
    return -1;
  }
  memcpy(g, gn, (size_t)c->m.nnodes * sizeof *g);
  *s = mpm_nonlocal_steady_field_stats(ws);
  mpm_nonlocal_free(ws);
  return 0;
}

/* ---- 1. against the 1D reference ---------------------------------------- */

/* Relative L2 error of the nodal g of row 0 against the reference. */
static double nodal_error(const cloud *c, const double *g, const ref *r)
{
  double num = 0.0, den = 0.0;
  for (int i = 0; i <= c->m.nx; i++) {
    double e = ref_at(r, i * c->m.dx), v = g[mpm_mesh_node(&c->m, i, 0, 0)];
    num += (v - e) * (v - e);
    den += e * e;
  }
  return sqrt(num / den);
}

/* The error at each level of refinement from 20 units, its value at the
 * finest against tol_fine and, when order is set, the observed order of the
 * last two levels against 2 +- 0.3. */
static void convergence(tally *t, const ref *r, int wall, int mass, int n, int levels,
                        double tol_fine, int order)
{
  double err[8] = {0};
  int nx0 = 20;
  char label[160];
  const char *wn = wall == MPM_NONLOCAL_WALL_NEUMANN ? "g' = 0" : "g = 0";
  for (int k = 0; k < levels; k++) {
    cloud c;
    const int nx = nx0 << k;
    if (make_cloud(&c, nx, n)) {
      report(t, "cloud", NAN, 0, 0);
      return;
    }
    double *g = malloc((size_t)c.m.nnodes * sizeof *g);
    mpm_linalg_stats s;
    if (granmpm_field(&c, wall, mass, g, &s) == 0) {
      err[k] = nodal_error(&c, g, r);
      snprintf(label, sizeof label, "walls %s, %s, %d x %d per unit, %d units: rel. L2 of nodal g",
               wn, mpm_nonlocal_steady_mass_name(mass), n, n, nx);
      printf("%-66s %11.4g\n", label, err[k]);
      if (s.fallback)
        report(t, "  Cholesky used (no fallback)", 1, 0, 0);
    } else {
      report(t, "granmpm solve", NAN, 0, 0);
    }
    free(g);
    free_cloud(&c);
  }
  snprintf(label, sizeof label, "walls %s, %s, %d x %d per unit: error at %d units", wn,
           mpm_nonlocal_steady_mass_name(mass), n, n, nx0 << (levels - 1));
  report(t, label, err[levels - 1], 0.0, tol_fine);
  if (!order)
    return;
  snprintf(label, sizeof label, "walls %s, %s, %d x %d per unit: order, %d -> %d units", wn,
           mpm_nonlocal_steady_mass_name(mass), n, n, nx0 << (levels - 2), nx0 << (levels - 1));
  report(t, label, log2(err[levels - 2] / err[levels - 1]), 1.7, 2.3);
}

/* ---- 2. against a dense solve assembled here ---------------------------- */

/* w = |mu - mu_s| / (A d)^2 and g_loc of [D-thesis] eq. 2.28-2.30 at x. */
static void terms(double x, double *w, double *gloc)
{
  const double mu = RHO * GRAV * fabs(x - 0.5 * L_W) / P0;
  *w = fabs(mu - MU_S) / (A_NL * A_NL * D_G * D_G);
  *gloc = mu > MU_S ? sqrt(P0 / RHO_S) / D_G * (mu - MU_S) / (B_LIN * mu) : 0.0;
}

/* Dense A g = b over all nodes (index i + (nx + 1) j, j periodic), held
 * rows replaced by g = 0; bilinear basis by hand. sign_left multiplies w on
 * the points with x < L/4. Gaussian elimination with partial pivoting. */
static int dense_solve(const cloud *c, int wall, int mass, double sign_left, double *g)
{
  const int nx = c->m.nx, ny = c->m.ny, nn = (nx + 1) * ny;
  const double dx = c->m.dx, dy = c->m.dy;
  double *A = calloc((size_t)nn * nn, sizeof *A), *b = calloc((size_t)nn, sizeof *b);
  for (size_t p = 0; p < c->P->n; p++) {
    const double x = c->P->x[p], y = c->P->y[p], V = c->P->vol[p];
    const int i = (int)(x / dx), j = (int)(y / dy);
    const double xi = x / dx - i, eta = y / dy - j;
    const int id[4] = {i + (nx + 1) * j, i + 1 + (nx + 1) * j, i + 1 + (nx + 1) * ((j + 1) % ny),
                       i + (nx + 1) * ((j + 1) % ny)};
    const double N[4] = {(1 - xi) * (1 - eta), xi * (1 - eta), xi * eta, (1 - xi) * eta};
    const double Nx[4] = {-(1 - eta) / dx, (1 - eta) / dx, eta / dx, -eta / dx};
    const double Ny[4] = {-(1 - xi) / dy, -xi / dy, xi / dy, (1 - xi) / dy};
    double w, gl;
    terms(x, &w, &gl);
    if (x < 0.25 * L_W)
      w *= sign_left;
    for (int a = 0; a < 4; a++) {
      b[id[a]] += V * w * N[a] * gl;
      for (int q = 0; q < 4; q++) {
        double v = V * (Nx[a] * Nx[q] + Ny[a] * Ny[q]);
        if (mass == MPM_STEADY_CONSISTENT)
          v += V * w * N[a] * N[q];
        else if (q == a)
          v += V * w * N[a];
        A[(size_t)id[a] * nn + id[q]] += v;
      }
    }
  }
  if (wall == MPM_NONLOCAL_WALL_DIRICHLET)
    for (int j = 0; j < ny; j++)
      for (int side = 0; side < 2; side++) {
        const int r = (side ? nx : 0) + (nx + 1) * j;
        for (int q = 0; q < nn; q++)
          A[(size_t)r * nn + q] = A[(size_t)q * nn + r] = 0.0;  /* g_r = 0: row, column */
        A[(size_t)r * nn + r] = 1.0;
        b[r] = 0.0;
      }
  int rc = 0;
  for (int k = 0; k < nn && !rc; k++) {
    int piv = k;
    for (int r = k + 1; r < nn; r++)
      if (fabs(A[(size_t)r * nn + k]) > fabs(A[(size_t)piv * nn + k]))
        piv = r;
    if (A[(size_t)piv * nn + k] == 0.0) {
      rc = -1;
      break;
    }
    if (piv != k) {
      for (int q = 0; q < nn; q++) {
        double tmp = A[(size_t)k * nn + q];
        A[(size_t)k * nn + q] = A[(size_t)piv * nn + q];
        A[(size_t)piv * nn + q] = tmp;
      }
      double tb = b[k];
      b[k] = b[piv];
      b[piv] = tb;
    }
    for (int r = k + 1; r < nn; r++) {
      const double f = A[(size_t)r * nn + k] / A[(size_t)k * nn + k];
      if (f == 0.0)
        continue;
      for (int q = k; q < nn; q++)
        A[(size_t)r * nn + q] -= f * A[(size_t)k * nn + q];
      b[r] -= f * b[k];
    }
  }
  for (int k = nn - 1; k >= 0 && !rc; k--) {
    double s = b[k];
    for (int q = k + 1; q < nn; q++)
      s -= A[(size_t)k * nn + q] * g[q];
    g[k] = s / A[(size_t)k * nn + k];
  }
  free(A);
  free(b);
  return rc;
}

/* Max |granmpm - dense| over the nodes, relative to max |dense|. */
static double dense_diff(const cloud *c, const double *gm, const double *gd)
{
  double e = 0.0, m = 0.0;
  for (int j = 0; j < c->m.ny; j++)
    for (int i = 0; i <= c->m.nx; i++) {
      const double d = gd[i + (c->m.nx + 1) * j];
      e = fmax(e, fabs(gm[mpm_mesh_node(&c->m, i, j, 0)] - d));
      m = fmax(m, fabs(d));
    }
  return e / m;
}

/* The system made indefinite on purpose: w = 1/xi^2 negated on the points
 * with x < L/4 (zero flux at the walls). The model gives w >= 0, so this
 * case goes to the steady solver directly (steady.h) with the w and g_loc of
 * terms(); Cholesky must stop and the QR fallback solve it as the dense
 * elimination does. */
static void indefinite(tally *t, const cloud *c, int mass)
{
  const size_t n = c->P->n;
  double *w = malloc(n * sizeof *w), *gl = malloc(n * sizeof *gl);
  unsigned char *dense = malloc(n), *held = calloc((size_t)c->m.nnodes, 1);
  for (size_t p = 0; p < n; p++) {
    terms(c->P->x[p], &w[p], &gl[p]);
    if (c->P->x[p] < 0.25 * L_W)
      w[p] = -w[p];
    dense[p] = 1;
  }
  mpm_err err = {0};
  mpm_nonlocal_steady *ss = mpm_nonlocal_steady_alloc(&c->m, &err);
  int rc = ss ? mpm_nonlocal_steady_solve(ss, c->st, &c->m, n, c->P->vol, w, gl, dense, held,
                                          mass, &err)
              : -1;
  double *gd = malloc((size_t)(c->m.nx + 1) * c->m.ny * sizeof *gd);
  char label[128];
  snprintf(label, sizeof label, "indefinite (w < 0 for x < L/4), %s: QR fallback used",
           mpm_nonlocal_steady_mass_name(mass));
  if (rc != MPM_OK || dense_solve(c, MPM_NONLOCAL_WALL_NEUMANN, mass, -1.0, gd)) {
    printf("  %s\n", err.msg);
    report(t, label, NAN, 1, 1);
  } else {
    report(t, label, mpm_nonlocal_steady_stats(ss).fallback, 1, 1);
    snprintf(label, sizeof label, "indefinite, %s: max |g - g_dense| / max |g_dense|",
             mpm_nonlocal_steady_mass_name(mass));
    report(t, label, dense_diff(c, mpm_nonlocal_steady_nodal(ss), gd), 0.0, 1e-10);
  }
  free(gd);
  mpm_nonlocal_steady_free(ss);
  free(w);
  free(gl);
  free(dense);
  free(held);
}

static void against_dense(tally *t)
{
  cloud c;
  if (make_cloud(&c, 20, 2)) {
    report(t, "cloud", NAN, 0, 0);
    return;
  }
  double *gm = malloc((size_t)c.m.nnodes * sizeof *gm);
  double *gd = malloc((size_t)(c.m.nx + 1) * c.m.ny * sizeof *gd);
  for (int wall = 0; wall < 2; wall++)
    for (int mass = 0; mass < 2; mass++) {
      mpm_linalg_stats s;
      char label[128];
      snprintf(label, sizeof label, "20 units, walls %s, %s: max |g - g_dense| / max |g_dense|",
               wall == MPM_NONLOCAL_WALL_NEUMANN ? "g' = 0" : "g = 0",
               mpm_nonlocal_steady_mass_name(mass));
      if (granmpm_field(&c, wall, mass, gm, &s) || dense_solve(&c, wall, mass, 1.0, gd)) {
        report(t, label, NAN, 0, 0);
        continue;
      }
      report(t, label, dense_diff(&c, gm, gd), 0.0, 1e-10);
      if (s.fallback)
        report(t, "  ... by Cholesky (fallback flag)", s.fallback, 0, 0);
    }
  indefinite(t, &c, MPM_STEADY_CONSISTENT);
  indefinite(t, &c, MPM_STEADY_LUMPED);
  free(gm);
  free(gd);
  free_cloud(&c);
}

int main(int argc, char **argv)
{
  if (argc < 3) {
    fprintf(stderr, "usage: v9 REF_NEUMANN REF_DIRICHLET [--quick]\n");
    return 2;
  }
  const int quick = argc > 3 && strcmp(argv[3], "--quick") == 0;
  ref rn, rd;
  if (read_ref(argv[1], &rn) || read_ref(argv[2], &rd)) {
    fprintf(stderr, "v9: cannot read the references %s, %s\n", argv[1], argv[2]);
    return 2;
  }
  tally t = {0};
  const int lv = quick ? 3 : 4;
  convergence(&t, &rn, MPM_NONLOCAL_WALL_NEUMANN, MPM_STEADY_CONSISTENT, 2, lv, 1e-3, 1);
  convergence(&t, &rn, MPM_NONLOCAL_WALL_NEUMANN, MPM_STEADY_LUMPED, 2, lv, 1e-3, 1);
  convergence(&t, &rn, MPM_NONLOCAL_WALL_NEUMANN, MPM_STEADY_CONSISTENT, 4, lv, 1e-3, 1);
  convergence(&t, &rn, MPM_NONLOCAL_WALL_NEUMANN, MPM_STEADY_LUMPED, 1, lv, 1e-3, 0);
  convergence(&t, &rd, MPM_NONLOCAL_WALL_DIRICHLET, MPM_STEADY_CONSISTENT, 2, lv, 1e-2, 1);
  against_dense(&t);
  free(rn.x);
  free(rn.g);
  free(rd.x);
  free(rd.g);
  printf("V9: %s (%d target(s) missed)\n", t.fails ? "FAIL" : "PASS", t.fails);
  return t.fails ? 1 : 0;
}
