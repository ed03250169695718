/* steady.c: the Galerkin solve of the steady fluidity on the mesh nodes
 * (steady.h; [D-thesis] section 3.5.2, eq. 3.82-3.86).
 *
 *   A_ij = sum_p V_p (w_p S_ip S_jp + gradS_ip . gradS_jp)   (lumped: w_p S_ip on i = j)
 *   b_i  = sum_p V_p w_p S_ip g_loc,p
 * over the dense points, unknowns the nodes they touch less the held ones.
 * Each point adds the lower triangle of its stencil's block as triplets
 * (duplicates are summed by the linalg corner), in point order: the matrix,
 * and so g, do not depend on the thread count. The mesh is of either
 * dimension (bilinear or trilinear elements; gradS . gradS over its axes). */
#include "nonlocal/steady.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "core/names.h"

static const char *const sample_names[] = {"element", "linear"};
static const char *const mass_names[] = {"consistent", "lumped"};

int mpm_nonlocal_steady_sample_from_name(const char *name)
{
  return mpm_names_index(sample_names, MPM_NAMES_COUNT(sample_names), name);
}

const char *mpm_nonlocal_steady_sample_name(int sample)
{
  return mpm_names_at(sample_names, MPM_NAMES_COUNT(sample_names), sample);
}

int mpm_nonlocal_steady_mass_from_name(const char *name)
{
  return mpm_names_index(mass_names, MPM_NAMES_COUNT(mass_names), name);
}

const char *mpm_nonlocal_steady_mass_name(int mass)
{
  return mpm_names_at(mass_names, MPM_NAMES_COUNT(mass_names), mass);
}

struct mpm_nonlocal_steady {
  mpm_linalg_spd *spd;
  int nnodes;
  int *row;              /* [nnodes] row of each node in the system, -1: not an unknown */
  int nrow;              /* unknowns of the last solve */
  double *g;             /* [nnodes] nodal g */
  double *b, *x;         /* [nnodes] right-hand side and solution, in row order */
  int *ti, *tj;          /* [tcap] triplets of the lower triangle */
  double *tv;
  size_t tcap;
};

void mpm_nonlocal_steady_free(mpm_nonlocal_steady *ss)
{
  if (!ss)
    return;
  mpm_linalg_spd_free(ss->spd);
  free(ss->row);
  free(ss->g);
  free(ss->b);
  free(ss->x);
  free(ss->ti);
  free(ss->tj);
  free(ss->tv);
  free(ss);
}

mpm_nonlocal_steady *mpm_nonlocal_steady_alloc(const mpm_mesh *m, mpm_err *err)
{
  mpm_nonlocal_steady *ss = calloc(1, sizeof *ss);
  const size_t nn = m->nnodes > 0 ? (size_t)m->nnodes : 1;
  if (ss) {
    ss->nnodes = m->nnodes;
    ss->row = malloc(nn * sizeof *ss->row);
    ss->g = calloc(nn, sizeof *ss->g);
    ss->b = malloc(nn * sizeof *ss->b);
    ss->x = malloc(nn * sizeof *ss->x);
  }
  if (!ss || !ss->row || !ss->g || !ss->b || !ss->x) {
    mpm_nonlocal_steady_free(ss);
    mpm_err_set(err, MPM_ENOMEM, "steady fluidity: no memory for %d nodes", m->nnodes);
    return NULL;
  }
  if (!(ss->spd = mpm_linalg_spd_alloc(err))) {
    mpm_nonlocal_steady_free(ss);
    return NULL;
  }
  return ss;
}

/* Room for at least need triplets. */
static int reserve_triplets(mpm_nonlocal_steady *ss, size_t need, mpm_err *err)
{
  if (need <= ss->tcap)
    return MPM_OK;
  size_t cap = need + need / 2;
  int *ti = realloc(ss->ti, cap * sizeof *ti);
  if (ti)
    ss->ti = ti;
  int *tj = realloc(ss->tj, cap * sizeof *tj);
  if (tj)
    ss->tj = tj;
  double *tv = realloc(ss->tv, cap * sizeof *tv);
  if (tv)
    ss->tv = tv;
  if (!ti || !tj || !tv)
    return mpm_err_set(err, MPM_ENOMEM, "steady fluidity: no memory for %zu matrix entries", cap);
  ss->tcap = cap;
  return MPM_OK;
}

/* A point's weights as a list (the stencil in either form) and its D. */
typedef struct point_weights {
  int node[MPM_STENCIL_W];
  double S[MPM_STENCIL_W], g[3][MPM_STENCIL_W];
} point_weights;

static int weights_of(const mpm_shape_stencil *st, const mpm_mesh *m, size_t p,
                      point_weights *pw)
{
  double *const dS[3] = {pw->g[0], pw->g[1], pw->g[2]};
  return mpm_shape_stencil_list(st, m, p, pw->node, pw->S, dS);
}

/* Number the unknowns: the nodes a dense point weighs (S or gradS not 0: a
 * stencil may list a node of weights 0), less the held ones, in node
 * order. Returns their count; counts the triplets in *ntrip. */
static int number_rows(mpm_nonlocal_steady *ss, const mpm_shape_stencil *st, const mpm_mesh *m,
                       size_t n, const unsigned char *dense, const unsigned char *held,
                       size_t *ntrip)
{
  for (int i = 0; i < ss->nnodes; i++)
    ss->row[i] = -1;
  *ntrip = 0;
  point_weights pw;
  for (size_t p = 0; p < n; p++) {
    if (!dense[p])
      continue;
    const int c = weights_of(st, m, p, &pw);
    for (int k = 0; k < c; k++) {
      int weighed = pw.S[k] != 0.0;
      for (int d = 0; d < m->dim; d++)
        weighed |= pw.g[d][k] != 0.0;
      if (weighed && !held[pw.node[k]])
        ss->row[pw.node[k]] = 0;
    }
    *ntrip += (size_t)c * (size_t)(c + 1) / 2;
  }
  int nrow = 0;
  for (int i = 0; i < ss->nnodes; i++)
    if (ss->row[i] == 0)
      ss->row[i] = nrow++;
    else
      ss->row[i] = -1;
  return nrow;
}

int mpm_nonlocal_steady_solve(mpm_nonlocal_steady *ss, const mpm_shape_stencil *st,
                              const mpm_mesh *m, size_t n, const double *vol, const double *w,
                              const double *gloc, const unsigned char *dense,
                              const unsigned char *held, int mass, mpm_err *err)
{
  size_t ntrip;
  const int nrow = number_rows(ss, st, m, n, dense, held, &ntrip);
  ss->nrow = nrow;
  for (int i = 0; i < ss->nnodes; i++)
    ss->g[i] = 0.0;
  if (nrow == 0)
    return MPM_OK;                                   /* nothing dense, or all held: g = 0 */
  int rc = reserve_triplets(ss, ntrip, err);
  if (rc != MPM_OK)
    return rc;
  for (int r = 0; r < nrow; r++)
    ss->b[r] = 0.0;
  const int lumped = mass == MPM_STEADY_LUMPED, D = m->dim;
  size_t t = 0;
  point_weights pw;
  for (size_t p = 0; p < n; p++) {
    if (!dense[p])
      continue;
    const double V = vol[p], wV = w[p] * V, bV = wV * gloc[p];   /* V w, V w g_loc */
    if (!isfinite(wV) || !isfinite(bV))
      return mpm_err_set(err, MPM_EINVAL,
                         "steady fluidity: point %zu has V/xi^2 = %g, V g_loc/xi^2 = %g", p, wV,
                         bV);
    const int c = weights_of(st, m, p, &pw);
    const double *S = pw.S;
    for (int k = 0; k < c; k++) {
      const int rk = ss->row[pw.node[k]];
      if (rk < 0)
        continue;                                    /* held: g = 0, row and column gone */
      ss->b[rk] += bV * S[k];                        /* b_i += V w S_i g_loc */
      for (int l = 0; l <= k; l++) {
        const int rl = ss->row[pw.node[l]];
        if (rl < 0)
          continue;
        double gg = pw.g[0][k] * pw.g[0][l];
        for (int d = 1; d < D; d++)
          gg += pw.g[d][k] * pw.g[d][l];
        double a = V * gg;                           /* V gradS_i . gradS_j */
        if (!lumped)
          a += wV * S[k] * S[l];                     /* + V w S_i S_j */
        else if (l == k)
          a += wV * S[k];                            /* + V w S_i (row sum) */
        if (l != k && rl == rk)
          a *= 2.0;                                  /* one node listed twice (a periodic axis of
                                                        one unit): the pair (k, l) and (l, k) */
        ss->ti[t] = rk;
        ss->tj[t] = rl;
        ss->tv[t] = a;
        t++;
      }
    }
  }
  int any = 0;
  for (int r = 0; r < nrow && !any; r++)
    any = ss->b[r] != 0.0;
  if (!any)
    return MPM_OK;                                   /* g_loc = 0 wherever w > 0: g = 0 */
  rc = mpm_linalg_spd_set(ss->spd, nrow, t, ss->ti, ss->tj, ss->tv, err);
  if (rc == MPM_OK && mpm_linalg_spd_pattern_changed(ss->spd))
    rc = mpm_linalg_spd_analyse(ss->spd, err);
  if (rc == MPM_OK)
    rc = mpm_linalg_spd_factor(ss->spd, err);
  if (rc == MPM_OK)
    rc = mpm_linalg_spd_solve(ss->spd, ss->b, ss->x, err);
  if (rc == MPM_ESOLVE && err && !lumped) {         /* a likely cause, said */
    char below[MPM_ERR_MSG];
    snprintf(below, sizeof below, "%s", err->msg);
    return mpm_err_set(err, rc, "steady fluidity on %d nodes: %s; a nodal mode the points do "
                       "not see, as the checkerboard mode for one point a unit side on the "
                       "units' centre planes (material.g_mass = \"lumped\", or fill.ppu >= 2)",
                       nrow, below);
  }
  if (rc != MPM_OK)
    return mpm_err_prefix(err, rc, "steady fluidity on %d nodes", nrow);
  for (int i = 0; i < ss->nnodes; i++)
    if (ss->row[i] >= 0)
      ss->g[i] = ss->x[ss->row[i]];
  return MPM_OK;
}

const double *mpm_nonlocal_steady_nodal(const mpm_nonlocal_steady *ss)
{
  return ss->g;
}

int mpm_nonlocal_steady_unknowns(const mpm_nonlocal_steady *ss)
{
  return ss->nrow;
}

double mpm_nonlocal_steady_point(const mpm_nonlocal_steady *ss, const mpm_mesh *m,
                                 const mpm_shape_stencil *st, const mpm_points *P, size_t p,
                                 int sample)
{
  double v = 0.0;
  if (sample == MPM_STEADY_LINEAR) {                 /* sum_i S_ip g_i */
    point_weights pw;
    const int c = weights_of(st, m, p, &pw);
    for (int k = 0; k < c; k++)
      v += pw.S[k] * ss->g[pw.node[k]];
  } else {                                           /* mean over the element's nodes */
    int node[8];
    double N[8], gx[8], gy[8], gz[8];
    double *const dN[3] = {gx, gy, gz};
    const double x[3] = {P->x[p], P->y[p], m->dim == 3 ? P->z[p] : 0.0};
    const int c = mpm_mesh_basis(m, x, node, N, dN);
    for (int k = 0; k < c; k++)
      v += ss->g[node[k]];
    v = c > 0 ? v / c : 0.0;
  }
  return v > 0.0 ? v : 0.0;
}

mpm_linalg_stats mpm_nonlocal_steady_stats(const mpm_nonlocal_steady *ss)
{
  return mpm_linalg_spd_stats(ss->spd);
}
