/* implicit.c: backward-Euler diffusion of the element fluidity on the unit
 * grid (implicit.h; docs/model.md, "Implicit diffusion").
 *
 *   (I - c L_h) g* = g_e on the filled units, c = (dt_sub/t0) A^2 d^2,
 *   L_h g_e = sum_s w_s (g_s - g_e), w = 1/dx^2 (W, E), 1/dy^2 (S, N),
 * g_s the filled neighbour across side s or the ghost k g_e (k = +1
 * Neumann, -1 Dirichlet; mpm_nonlocal_side). Row of unit e:
 *   diagonal  1 + c sum_{s: neighbour} w_s + c sum_{s: ghost} (1 - k_s) w_s
 *   neighbour -c w_s
 * (Neumann ghosts cancel, Dirichlet ghosts add 2 c w_s; a periodic axis of
 * two units gives one neighbour twice, -2 c w_s, summed by the corner). Then
 *   lap_e = (g*_e - g_e) / c   (= L_h g*_e). */
#include "nonlocal/implicit.h"

#include <math.h>
#include <stdlib.h>

struct mpm_nonlocal_implicit {
  mpm_linalg_spd *spd;
  int nx, ny;
  size_t nu;             /* units nx ny */
  int *row;              /* [nu] row of each unit in the system, -1 when empty */
  int nf;                /* rows (filled units) */
  double c;              /* c of the factor */
  int factored;          /* the factor holds the current rows, c and ghost rules */
  unsigned stamp;        /* ghost_stamp of the workspace when factored */
  int *ti, *tj;          /* [5 nu] triplets of the lower triangle */
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
  free(im->ti);
  free(im->tj);
  free(im->tv);
  free(im->b);
  free(im->x);
  free(im->gs);
  free(im);
}

mpm_nonlocal_implicit *mpm_nonlocal_implicit_alloc(const mpm_nonlocal *ws, mpm_err *err)
{
  mpm_nonlocal_implicit *im = calloc(1, sizeof *im);
  if (!im) {
    mpm_err_set(err, MPM_ENOMEM, "nonlocal: no memory for the implicit diffusion");
    return NULL;
  }
  im->nx = ws->nx;
  im->ny = ws->ny;
  im->nu = (size_t)ws->nx * (size_t)ws->ny;
  const size_t nt = 5 * im->nu;                        /* diagonal + up to 4 neighbours */
  im->row = malloc(im->nu * sizeof *im->row);
  im->ti = malloc(nt * sizeof *im->ti);
  im->tj = malloc(nt * sizeof *im->tj);
  im->tv = malloc(nt * sizeof *im->tv);
  im->b = malloc(im->nu * sizeof *im->b);
  im->x = malloc(im->nu * sizeof *im->x);
  im->gs = calloc(im->nu, sizeof *im->gs);
  if (!im->row || !im->ti || !im->tj || !im->tv || !im->b || !im->x || !im->gs) {
    mpm_nonlocal_implicit_free(im);
    mpm_err_set(err, MPM_ENOMEM, "nonlocal: no memory for the implicit diffusion on %zu units",
                (size_t)ws->nx * (size_t)ws->ny);
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

const double *mpm_nonlocal_implicit_gstar(const mpm_nonlocal_implicit *im)
{
  return im->gs;
}

mpm_linalg_stats mpm_nonlocal_implicit_stats(const mpm_nonlocal_implicit *im)
{
  return mpm_linalg_spd_stats(im->spd);
}

/* 1 if the filled units of ws are the rows of the factor. */
static int same_set(const mpm_nonlocal_implicit *im, const mpm_nonlocal *ws)
{
  for (size_t e = 0; e < im->nu; e++)
    if ((ws->sm[e] > 0.0) != (im->row[e] >= 0))
      return 0;
  return 1;
}

/* Rows for the filled units, in unit order; their number. */
static int number_rows(mpm_nonlocal_implicit *im, const mpm_nonlocal *ws)
{
  int r = 0;
  for (size_t e = 0; e < im->nu; e++)
    im->row[e] = ws->sm[e] > 0.0 ? r++ : -1;
  return r;
}

/* Triplets of the lower triangle of I - c L_h (see the top); their number. */
static size_t assemble(mpm_nonlocal_implicit *im, const mpm_nonlocal *ws, double c)
{
  size_t k = 0;
  for (int j = 0; j < ws->ny; j++)
    for (int i = 0; i < ws->nx; i++) {
      const size_t e = (size_t)i + (size_t)ws->nx * (size_t)j;
      const int r = im->row[e];
      if (r < 0)
        continue;
      double diag = 1.0;
      for (int s = MPM_SIDE_W; s <= MPM_SIDE_N; s++) {
        const double cw = c * (s <= MPM_SIDE_E ? ws->idx2 : ws->idy2);  /* c w_s */
        size_t nb = 0;
        const int kg = mpm_nonlocal_side(ws, i, j, s, &nb);
        if (kg != 0) {
          diag += (1 - kg) * cw;                       /* ghost k g_e: 0 or 2 c w_s */
          continue;
        }
        const int rn = im->row[nb];
        if (rn == r)
          continue;                                    /* own neighbour: g_s - g_e = 0 */
        diag += cw;
        if (rn < r) {                                  /* each pair once, from its lower row */
          im->ti[k] = r;
          im->tj[k] = rn;
          im->tv[k++] = -cw;
        }
      }
      im->ti[k] = r;
      im->tj[k] = r;
      im->tv[k++] = diag;
    }
  return k;
}

/* Analysis (new set), factorisation (new set or c) as needed. */
static int prepare(mpm_nonlocal_implicit *im, const mpm_nonlocal *ws, double c, mpm_err *err)
{
  const int new_set = !im->factored || !same_set(im, ws);
  if (!new_set && c == im->c && im->stamp == ws->ghost_stamp)
    return MPM_OK;
  im->factored = 0;
  if (new_set)
    im->nf = number_rows(im, ws);
  size_t nt = assemble(im, ws, c);
  int rc = mpm_linalg_spd_set(im->spd, im->nf, nt, im->ti, im->tj, im->tv, err);
  if (rc == MPM_OK && new_set)
    rc = mpm_linalg_spd_analyse(im->spd, err);
  if (rc == MPM_OK)
    rc = mpm_linalg_spd_factor(im->spd, err);
  if (rc != MPM_OK)
    return rc;
  im->c = c;
  im->stamp = ws->ghost_stamp;
  im->factored = 1;
  return MPM_OK;
}

int mpm_nonlocal_implicit_laplacian(mpm_nonlocal_implicit *im, mpm_nonlocal *ws, double c,
                                    mpm_err *err)
{
  if (ws->nx != im->nx || ws->ny != im->ny)
    return mpm_err_set(err, MPM_EINVAL,
                       "nonlocal: implicit diffusion set up for %d x %d units, given %d x %d",
                       im->nx, im->ny, ws->nx, ws->ny);
  if (!(c >= 0.0 && isfinite(c)))
    return mpm_err_set(err, MPM_EINVAL,
                       "nonlocal: implicit diffusion coefficient c = %g m^2 (must be >= 0)", c);
  if (c == 0.0) {                                      /* g* = g_e: the explicit lap_e */
    mpm_nonlocal_laplacian(ws);
    return MPM_OK;
  }
  size_t e0 = 0;
  while (e0 < im->nu && !(ws->sm[e0] > 0.0))
    e0++;
  if (e0 == im->nu)
    return mpm_err_set(err, MPM_EINVAL, "nonlocal: implicit diffusion with no filled unit "
                       "(empty system)");
  int rc = prepare(im, ws, c, err);
  if (rc == MPM_OK) {
    for (size_t e = 0; e < im->nu; e++)
      if (im->row[e] >= 0)
        im->b[im->row[e]] = ws->ge[e];                 /* b = g_e */
    rc = mpm_linalg_spd_solve(im->spd, im->b, im->x, err);
  }
  if (rc != MPM_OK)
    return mpm_err_prefix(err, rc, "nonlocal: implicit diffusion on %d filled units, c = %.6g m^2",
                          im->nf, c);
  for (size_t e = 0; e < im->nu; e++) {
    const int r = im->row[e];
    im->gs[e] = r >= 0 ? im->x[r] : 0.0;               /* g*_e */
    ws->lap[e] = r >= 0 ? (im->gs[e] - ws->ge[e]) / c : 0.0;  /* (g* - g_e)/c = L_h g* */
  }
  return MPM_OK;
}
