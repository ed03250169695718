/* implicit.c: backward-Euler diffusion of the element fluidity on the unit
 * grid of 2 or 3 dimensions (implicit.h; docs/model.md, "Implicit
 * diffusion").
 *
 *   (I - c L_h) g* = g_e on the filled units, c = (dt_sub/t0) A^2 d^2,
 *   L_h g_e = sum_f w_f (g_f - g_e), w = 1/dx^2 (W, E), 1/dy^2 (S, N),
 *   1/dz^2 (bottom, top in 3D),
 * g_f the filled neighbour across face f or the ghost k g_e (k = +1
 * Neumann, -1 Dirichlet; mpm_nonlocal_grid_side). Row of unit e
 * (mpm_nonlocal_grid_row, the one row builder of both dimensions):
 *   diagonal  1 + c sum_{f: neighbour} w_f + c sum_{f: ghost} (1 - k_f) w_f
 *   neighbour -c w_f
 * (Neumann ghosts cancel, Dirichlet ghosts add 2 c w_f; a periodic axis of
 * two units gives one neighbour twice, -2 c w_f, summed by the corner). Then
 *   lap_e = (g*_e - g_e) / c   (= L_h g*_e).
 *
 * The system's rows are the covered units: every unit that has been filled
 * at some solve (the cover only grows). A covered unit that is empty now is
 * the identity row 1 g* = 0, and every pair of face-adjacent covered units
 * keeps its entry (zero when either is empty), so the pattern, and with it
 * the AMD ordering and the symbolic analysis, changes only when material
 * reaches a unit for the first time; a filled set that moves inside the
 * cover costs only a numeric factorisation. The filled rows are those of
 * the filled set alone (an empty row is decoupled: its zero entries add
 * nothing), so g* is the same up to the round-off of the ordering. */
#include "nonlocal/implicit.h"

#include <math.h>
#include <stdlib.h>

struct mpm_nonlocal_implicit {
  mpm_linalg_spd *spd;
  int dim, n[3];         /* the grid's dimensions and units along each axis */
  size_t nu;             /* units n_0 n_1 n_2 */
  int *row;              /* [nu] row of each unit in the system, -1 when not covered */
  unsigned char *filled; /* [nu] the filled set of the factor */
  int nr;                /* rows (covered units) */
  int nf;                /* filled units */
  double c;              /* c of the factor */
  int factored;          /* the factor holds the current rows, c and ghost rules */
  unsigned stamp;        /* ghost_stamp of the workspace when factored */
  int *ti, *tj;          /* [(1 + 2 dim) nu] triplets of the lower triangle */
  double *tv;
  double *b, *x;         /* [nu] right-hand side and solution, in row order */
  double *gs;            /* [nu] g* per unit */
};

void mpm_nonlocal_implicit_free(mpm_nonlocal_implicit *im)
{
  if (!im)
    return;
  mpm_linalg_spd_free(im->spd);
  free(im->row);
  free(im->filled);
  free(im->ti);
  free(im->tj);
  free(im->tv);
  free(im->b);
  free(im->x);
  free(im->gs);
  free(im);
}

mpm_nonlocal_implicit *mpm_nonlocal_implicit_alloc_grid(const mpm_nonlocal_grid *g,
                                                        mpm_err *err)
{
  mpm_nonlocal_implicit *im = calloc(1, sizeof *im);
  if (!im) {
    mpm_err_set(err, MPM_ENOMEM, "nonlocal: no memory for the implicit diffusion");
    return NULL;
  }
  im->dim = g->dim;
  for (int a = 0; a < 3; a++)
    im->n[a] = g->n[a];
  im->nu = g->nu;
  const size_t nt = (size_t)(1 + 2 * g->dim) * im->nu;  /* diagonal + up to 2 dim neighbours */
  im->row = malloc(im->nu * sizeof *im->row);
  im->filled = calloc(im->nu, 1);
  im->ti = malloc(nt * sizeof *im->ti);
  im->tj = malloc(nt * sizeof *im->tj);
  im->tv = malloc(nt * sizeof *im->tv);
  im->b = malloc(im->nu * sizeof *im->b);
  im->x = malloc(im->nu * sizeof *im->x);
  im->gs = calloc(im->nu, sizeof *im->gs);
  if (!im->row || !im->filled || !im->ti || !im->tj || !im->tv || !im->b || !im->x || !im->gs) {
    mpm_nonlocal_implicit_free(im);
    mpm_err_set(err, MPM_ENOMEM, "nonlocal: no memory for the implicit diffusion on %zu units",
                g->nu);
    return NULL;
  }
  im->spd = mpm_linalg_spd_alloc(err);
  if (!im->spd) {
    mpm_nonlocal_implicit_free(im);
    return NULL;
  }
  for (size_t e = 0; e < im->nu; e++)
    im->row[e] = -1;
  return im;
}

mpm_nonlocal_implicit *mpm_nonlocal_implicit_alloc(const mpm_nonlocal *ws, mpm_err *err)
{
  return mpm_nonlocal_implicit_alloc_grid(&ws->grid, err);
}

const double *mpm_nonlocal_implicit_gstar(const mpm_nonlocal_implicit *im)
{
  return im->gs;
}

mpm_linalg_stats mpm_nonlocal_implicit_stats(const mpm_nonlocal_implicit *im)
{
  return mpm_linalg_spd_stats(im->spd);
}

/* 1 if the filled units (sm > 0) are the filled set of the factor. */
static int same_set(const mpm_nonlocal_implicit *im, const double *sm)
{
  for (size_t e = 0; e < im->nu; e++)
    if ((sm[e] > 0.0) != im->filled[e])
      return 0;
  return 1;
}

/* The filled set from sm, and rows for it: the cover grows by the filled
 * units it lacks and is numbered again in unit order (a new pattern, which
 * mpm_linalg_spd_set then finds). */
static void take_set(mpm_nonlocal_implicit *im, const double *sm)
{
  int grew = 0;
  im->nf = 0;
  for (size_t e = 0; e < im->nu; e++) {
    im->filled[e] = sm[e] > 0.0;
    im->nf += im->filled[e];
    grew |= im->filled[e] && im->row[e] < 0;
  }
  if (grew) {
    int r = 0;
    for (size_t e = 0; e < im->nu; e++)
      im->row[e] = im->row[e] >= 0 || im->filled[e] ? r++ : -1;
    im->nr = r;
  }
}

/* Triplets of the lower triangle of the covered rows, units in index order:
 * a filled unit's row of I - c L_h (mpm_nonlocal_grid_row), an empty
 * covered unit's identity row, and a zero for every face-adjacent covered
 * pair the filled rows leave out (the fixed pattern). Their number. */
static size_t assemble(mpm_nonlocal_implicit *im, const mpm_nonlocal_grid *g, const double *sm,
                       double c)
{
  size_t k = 0;
  int u[3];
  size_t e = 0;
  for (u[2] = 0; u[2] < g->n[2]; u[2]++)
    for (u[1] = 0; u[1] < g->n[1]; u[1]++)
      for (u[0] = 0; u[0] < g->n[0]; u[0]++, e++) {
        const int r = im->row[e];
        if (r < 0)
          continue;
        size_t nb[MPM_NONLOCAL_FACES];
        double val[MPM_NONLOCAL_FACES];
        int cnt = 0;
        double diag = 1.0;
        if (im->filled[e])
          diag = mpm_nonlocal_grid_row(g, sm, u, e, c, nb, val, &cnt);
        for (int q = 0; q < cnt; q++) {
          const int rn = im->row[nb[q]];
          if (rn < r) {                                /* each pair once, from its lower row */
            im->ti[k] = r;
            im->tj[k] = rn;
            im->tv[k++] = val[q];
          }
        }
        for (int f = 0; f < 2 * g->dim; f++) {         /* the pattern's zeros */
          size_t q = 0;
          if (mpm_nonlocal_grid_side(g, sm, u, e, f, &q) == 0 && im->filled[e])
            continue;                                  /* a filled pair: its value above */
          if (mpm_nonlocal_grid_face_unit(g, u, e, f, &q) && q != e && im->row[q] >= 0 &&
              im->row[q] < r) {
            im->ti[k] = r;
            im->tj[k] = im->row[q];
            im->tv[k++] = 0.0;
          }
        }
        im->ti[k] = r;
        im->tj[k] = r;
        im->tv[k++] = diag;
      }
  return k;
}

/* Analysis (a new pattern: the cover grew, or a periodic rule changed),
 * factorisation (a new filled set, c or ghost rules) as needed. */
static int prepare(mpm_nonlocal_implicit *im, const mpm_nonlocal_grid *g, const double *sm,
                   double c, mpm_err *err)
{
  const int new_set = !im->factored || !same_set(im, sm);
  if (!new_set && c == im->c && im->stamp == g->stamp)
    return MPM_OK;
  im->factored = 0;
  if (new_set)
    take_set(im, sm);
  size_t nt = assemble(im, g, sm, c);
  int rc = mpm_linalg_spd_set(im->spd, im->nr, nt, im->ti, im->tj, im->tv, err);
  if (rc == MPM_OK && mpm_linalg_spd_pattern_changed(im->spd))
    rc = mpm_linalg_spd_analyse(im->spd, err);
  if (rc == MPM_OK)
    rc = mpm_linalg_spd_factor(im->spd, err);
  if (rc != MPM_OK)
    return rc;
  im->c = c;
  im->stamp = g->stamp;
  im->factored = 1;
  return MPM_OK;
}

int mpm_nonlocal_implicit_grid(mpm_nonlocal_implicit *im, const mpm_nonlocal_grid *g,
                               const double *sm, const double *ge, double *lap, double c,
                               mpm_err *err)
{
  if (g->dim != im->dim || g->n[0] != im->n[0] || g->n[1] != im->n[1] || g->n[2] != im->n[2]) {
    if (im->dim == 2 && g->dim == 2)
      return mpm_err_set(err, MPM_EINVAL,
                         "nonlocal: implicit diffusion set up for %d x %d units, given %d x %d",
                         im->n[0], im->n[1], g->n[0], g->n[1]);
    return mpm_err_set(err, MPM_EINVAL, "nonlocal: implicit diffusion set up for %d x %d x %d "
                       "units (%dD), given %d x %d x %d (%dD)", im->n[0], im->n[1], im->n[2],
                       im->dim, g->n[0], g->n[1], g->n[2], g->dim);
  }
  if (!(c >= 0.0 && isfinite(c)))
    return mpm_err_set(err, MPM_EINVAL,
                       "nonlocal: implicit diffusion coefficient c = %g m^2 (must be >= 0)", c);
  if (c == 0.0) {                                      /* g* = g_e: the explicit lap_e */
    mpm_nonlocal_grid_laplacian(g, sm, ge, lap);
    return MPM_OK;
  }
  size_t e0 = 0;
  while (e0 < im->nu && !(sm[e0] > 0.0))
    e0++;
  if (e0 == im->nu)
    return mpm_err_set(err, MPM_EINVAL, "nonlocal: implicit diffusion with no filled unit "
                       "(empty system)");
  int rc = prepare(im, g, sm, c, err);
  if (rc == MPM_OK) {
    for (size_t e = 0; e < im->nu; e++)
      if (im->row[e] >= 0)
        im->b[im->row[e]] = im->filled[e] ? ge[e] : 0.0;  /* b = g_e; 0 on empty rows */
    rc = mpm_linalg_spd_solve(im->spd, im->b, im->x, err);
  }
  if (rc != MPM_OK)
    return mpm_err_prefix(err, rc, "nonlocal: implicit diffusion on %d filled units, c = %.6g m^2",
                          im->nf, c);
  for (size_t e = 0; e < im->nu; e++) {
    const int in = im->filled[e];
    im->gs[e] = in ? im->x[im->row[e]] : 0.0;          /* g*_e */
    lap[e] = in ? (im->gs[e] - ge[e]) / c : 0.0;       /* (g* - g_e)/c = L_h g* */
  }
  return MPM_OK;
}

int mpm_nonlocal_implicit_laplacian(mpm_nonlocal_implicit *im, mpm_nonlocal *ws, double c,
                                    mpm_err *err)
{
  return mpm_nonlocal_implicit_grid(im, &ws->grid, ws->sm, ws->ge, ws->lap, c, err);
}
