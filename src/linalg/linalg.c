/* linalg.c: sparse SPD solves with CHOLMOD (simplicial LL', AMD ordering)
 * and a CSparse QR fallback (see linalg.h).
 *
 *   A = L L' (P A P' with the AMD permutation P): analyse once per pattern,
 *   factor once per set of values, then x = P' L'^-1 L^-1 P b per solve.
 *   Fallback where Cholesky stops: P_r A(:, q) = Q R (Householder
 *   reflections H_0 ... H_{n-1}, Q = H_0 ... H_{n-1}; column order AMD on
 *   A'A), x = q R^-1 Q' P_r b.
 * CHOLMOD is told not to print (print level 0, no error handler). */
#include "linalg/linalg.h"

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cholmod.h>
#include <cs.h>

struct mpm_linalg_spd {
  cholmod_common cm;
  cholmod_sparse *A;     /* current matrix, lower triangle (stype -1), sorted and packed */
  cholmod_factor *L;     /* symbolic or numeric factor of the analysed pattern */
  cholmod_dense *B, *X, *Y, *E;  /* right-hand side and cholmod_solve2 workspace */
  int *pat_p, *pat_i;    /* analysed pattern: column pointers [pat_n + 1], rows */
  int pat_n;
  int same_pattern;      /* A has the analysed pattern */
  int factored;          /* the factor holds A's current values */
  cs_dis *S;             /* QR fallback: ordering, factor and work vector */
  cs_din *N;
  double *work;
  mpm_linalg_stats st;
};

mpm_linalg_spd *mpm_linalg_spd_alloc(mpm_err *err)
{
  mpm_linalg_spd *s = calloc(1, sizeof *s);
  if (!s) {
    mpm_err_set(err, MPM_ENOMEM, "linalg: no memory for the solver");
    return NULL;
  }
  if (!cholmod_start(&s->cm)) {
    free(s);
    mpm_err_set(err, MPM_ESOLVE, "linalg: CHOLMOD did not start");
    return NULL;
  }
  s->cm.print = 0;                           /* the library never prints */
  s->cm.error_handler = NULL;
  s->cm.nmethods = 1;                        /* AMD only */
  s->cm.method[0].ordering = CHOLMOD_AMD;
  s->cm.postorder = 1;
  s->cm.supernodal = CHOLMOD_SIMPLICIAL;     /* no BLAS: thread-count free */
  s->cm.final_ll = 1;                        /* LL': fails where A is not SPD */
  s->st.failed_col = -1;
  return s;
}

static void free_qr(mpm_linalg_spd *s)
{
  s->N = cs_di_nfree(s->N);
  s->S = cs_di_sfree(s->S);
  s->st.fallback = 0;
}

void mpm_linalg_spd_free(mpm_linalg_spd *s)
{
  if (!s)
    return;
  free_qr(s);
  free(s->work);
  free(s->pat_p);
  free(s->pat_i);
  cholmod_free_sparse(&s->A, &s->cm);
  cholmod_free_factor(&s->L, &s->cm);
  cholmod_free_dense(&s->B, &s->cm);
  cholmod_free_dense(&s->X, &s->cm);
  cholmod_free_dense(&s->Y, &s->cm);
  cholmod_free_dense(&s->E, &s->cm);
  cholmod_finish(&s->cm);
  free(s);
}

mpm_linalg_stats mpm_linalg_spd_stats(const mpm_linalg_spd *s)
{
  return s->st;
}

/* MPM_ENOMEM or MPM_ESOLVE from CHOLMOD's status, with what was done. */
static int cholmod_fail(const mpm_linalg_spd *s, const char *what, int n, mpm_err *err)
{
  if (s->cm.status == CHOLMOD_OUT_OF_MEMORY || s->cm.status == CHOLMOD_TOO_LARGE)
    return mpm_err_set(err, MPM_ENOMEM, "linalg: out of memory in the %s of a %d x %d matrix",
                       what, n, n);
  return mpm_err_set(err, MPM_ESOLVE, "linalg: CHOLMOD %s of a %d x %d matrix failed (status %d)",
                     what, n, n, s->cm.status);
}

/* 1 if A's pattern is the analysed one. */
static int pattern_is_analysed(const mpm_linalg_spd *s)
{
  const cholmod_sparse *A = s->A;
  if (!s->pat_p || (int)A->ncol != s->pat_n)
    return 0;
  const int *ap = A->p, *ai = A->i;
  if (memcmp(ap, s->pat_p, (size_t)(s->pat_n + 1) * sizeof *ap) != 0)
    return 0;
  return memcmp(ai, s->pat_i, (size_t)ap[s->pat_n] * sizeof *ai) == 0;
}

int mpm_linalg_spd_set(mpm_linalg_spd *s, int n, size_t nnz, const int *row, const int *col,
                       const double *val, mpm_err *err)
{
  if (n < 1)
    return mpm_err_set(err, MPM_EINVAL, "linalg: empty system (%d x %d)", n, n);
  for (size_t k = 0; k < nnz; k++) {
    if (row[k] < 0 || row[k] >= n || col[k] < 0 || col[k] >= n)
      return mpm_err_set(err, MPM_EINVAL,
                         "linalg: entry %zu at (%d, %d) outside the %d x %d matrix", k, row[k],
                         col[k], n, n);
    if (!isfinite(val[k]))
      return mpm_err_set(err, MPM_EINVAL, "linalg: entry %zu at (%d, %d) is not finite (%g)",
                         k, row[k], col[k], val[k]);
  }
  cholmod_triplet *T = cholmod_allocate_triplet((size_t)n, (size_t)n, nnz > 0 ? nnz : 1, -1,
                                                CHOLMOD_REAL, &s->cm);
  if (!T)
    return cholmod_fail(s, "triplet allocation", n, err);
  int *ti = T->i, *tj = T->j;
  double *tx = T->x;
  for (size_t k = 0; k < nnz; k++) {         /* stype -1: upper entries are transposed */
    ti[k] = row[k];
    tj[k] = col[k];
    tx[k] = val[k];
  }
  T->nnz = nnz;
  cholmod_sparse *A = cholmod_triplet_to_sparse(T, 0, &s->cm);  /* sums duplicates */
  cholmod_free_triplet(&T, &s->cm);
  if (!A)
    return cholmod_fail(s, "conversion", n, err);
  cholmod_free_sparse(&s->A, &s->cm);
  s->A = A;
  s->same_pattern = pattern_is_analysed(s);
  s->factored = 0;
  free_qr(s);
  s->st.n = n;
  return MPM_OK;
}

int mpm_linalg_spd_pattern_changed(const mpm_linalg_spd *s)
{
  return !s->A || !s->same_pattern;
}

int mpm_linalg_spd_analyse(mpm_linalg_spd *s, mpm_err *err)
{
  if (!s->A)
    return mpm_err_set(err, MPM_EINVAL, "linalg: analyse without a matrix");
  const int n = (int)s->A->ncol;
  const int *ap = s->A->p;
  int *pp = malloc((size_t)(n + 1) * sizeof *pp);
  int *pi = malloc((size_t)(ap[n] > 0 ? ap[n] : 1) * sizeof *pi);
  if (!pp || !pi) {
    free(pp);
    free(pi);
    return mpm_err_set(err, MPM_ENOMEM, "linalg: no memory for the pattern of a %d x %d matrix",
                       n, n);
  }
  cholmod_free_factor(&s->L, &s->cm);
  free(s->pat_p);
  free(s->pat_i);
  s->pat_p = NULL;
  s->pat_i = NULL;
  s->same_pattern = 0;
  s->factored = 0;
  s->L = cholmod_analyze(s->A, &s->cm);      /* AMD, postordered */
  if (!s->L) {
    free(pp);
    free(pi);
    return cholmod_fail(s, "analysis", n, err);
  }
  memcpy(pp, ap, (size_t)(n + 1) * sizeof *pp);
  memcpy(pi, s->A->i, (size_t)ap[n] * sizeof *pi);
  s->pat_p = pp;
  s->pat_i = pi;
  s->pat_n = n;
  s->same_pattern = 1;
  s->st.analyses++;
  return MPM_OK;
}

/* Householder QR of the full matrix (both triangles of A), rows and
 * columns ordered by CSparse (AMD on A'A). On failure returns MPM_ENOMEM or
 * MPM_ESOLVE (a diagonal entry of R zero or below n eps times the largest)
 * and says why in why[len]. */
static int factor_qr(mpm_linalg_spd *s, char *why, size_t len)
{
  const cholmod_sparse *A = s->A;
  const int n = (int)A->ncol;
  const int *ap = A->p, *ai = A->i;
  const double *ax = A->x;
  cs_di *T = cs_di_spalloc(n, n, 2 * ap[n] > 0 ? 2 * ap[n] : 1, 1, 1);
  cs_di *C = NULL;
  if (T) {
    for (int j = 0; j < n; j++)
      for (int k = ap[j]; k < ap[j + 1]; k++) {
        cs_di_entry(T, ai[k], j, ax[k]);       /* lower entry (i, j) */
        if (ai[k] != j)
          cs_di_entry(T, j, ai[k], ax[k]);     /* and its mirror (j, i) */
      }
    C = cs_di_compress(T);
  }
  cs_di_spfree(T);
  s->S = C ? cs_di_sqr(3, C, 1) : NULL;        /* AMD on A'A, QR analysis */
  double *w = s->S ? realloc(s->work, (size_t)s->S->m2 * sizeof *w) : NULL;
  if (w)
    s->work = w;
  if (!C || !s->S || !w) {
    cs_di_spfree(C);
    free_qr(s);
    snprintf(why, len, "no memory for the QR fallback");
    return MPM_ENOMEM;
  }
  s->N = cs_di_qr(C, s->S);
  cs_di_spfree(C);
  if (!s->N) {
    free_qr(s);
    snprintf(why, len, "no memory for the QR fallback");
    return MPM_ENOMEM;
  }
  const cs_di *R = s->N->U;
  double rmax = 0.0, rmin = INFINITY;
  int kmin = 0;
  for (int k = 0; k < n; k++) {
    double d = R->p[k + 1] > R->p[k] ? fabs(R->x[R->p[k + 1] - 1]) : 0.0;  /* |r_kk|, last */
    rmax = fmax(rmax, d);
    if (d < rmin) {
      rmin = d;
      kmin = k;
    }
  }
  if (!(rmin > n * DBL_EPSILON * rmax)) {
    int col = s->S->q ? s->S->q[kmin] : kmin;
    free_qr(s);
    snprintf(why, len, "singular for QR too (|r_kk| %.3g of largest %.3g at column %d)", rmin,
             rmax, col);
    return MPM_ESOLVE;
  }
  s->st.fallback = 1;
  return MPM_OK;
}

int mpm_linalg_spd_factor(mpm_linalg_spd *s, mpm_err *err)
{
  if (!s->A || !s->L || !s->same_pattern)
    return mpm_err_set(err, MPM_EINVAL, "linalg: factor of a pattern not analysed");
  const int n = (int)s->A->ncol;
  s->factored = 0;
  free_qr(s);
  s->st.factors++;
  s->st.failed_col = -1;
  if (!cholmod_factorize(s->A, s->L, &s->cm) || s->cm.status < 0)
    return cholmod_fail(s, "factorisation", n, err);
  if (s->cm.status == CHOLMOD_NOT_POSDEF) {
    s->st.failed_col = (long)s->L->minor;     /* first column where L L' stopped */
    s->st.fallbacks++;
    char why[MPM_ERR_MSG / 2];
    int rc = factor_qr(s, why, sizeof why);
    if (rc != MPM_OK)
      return mpm_err_set(err, rc,
                         "linalg: Cholesky of a %d x %d matrix failed at column %ld (not "
                         "positive definite); %s", n, n, s->st.failed_col, why);
  } else {
    double rc = cholmod_rcond(s->L, &s->cm); /* (min/max of diag L)^2 */
    if (!(rc > n * DBL_EPSILON))
      return mpm_err_set(err, MPM_ESOLVE,
                         "linalg: %d x %d matrix is numerically singular (rcond %.3g)", n, n, rc);
  }
  s->factored = 1;
  return MPM_OK;
}

/* x = A^-1 b with the QR fallback: x = q R^-1 Q' P_r b. */
static void solve_qr(const mpm_linalg_spd *s, int n, const double *b, double *x)
{
  double *w = s->work;
  for (int i = 0; i < s->S->m2; i++)
    w[i] = 0.0;                              /* fictitious rows of the analysis stay 0 */
  cs_di_ipvec(s->S->pinv, b, w, n);          /* w = P_r b */
  for (int k = 0; k < n; k++)
    cs_di_happly(s->N->L, k, s->N->B[k], w); /* w = H_k w: Q' P_r b */
  cs_di_usolve(s->N->U, w);                  /* R^-1 */
  cs_di_ipvec(s->S->q, w, x, n);             /* x = q w */
}

int mpm_linalg_spd_solve(mpm_linalg_spd *s, const double *b, double *x, mpm_err *err)
{
  if (!s->factored)
    return mpm_err_set(err, MPM_EINVAL, "linalg: solve without a factorisation");
  const int n = (int)s->A->ncol;
  if (s->st.fallback) {
    solve_qr(s, n, b, x);
  } else {
    if (!s->B || (int)s->B->nrow != n) {
      cholmod_free_dense(&s->B, &s->cm);
      s->B = cholmod_allocate_dense((size_t)n, 1, (size_t)n, CHOLMOD_REAL, &s->cm);
      if (!s->B)
        return cholmod_fail(s, "solve", n, err);
    }
    memcpy(s->B->x, b, (size_t)n * sizeof *b);
    if (!cholmod_solve2(CHOLMOD_A, s->L, s->B, NULL, &s->X, NULL, &s->Y, &s->E, &s->cm))
      return cholmod_fail(s, "solve", n, err);
    memcpy(x, s->X->x, (size_t)n * sizeof *x);
  }
  s->st.solves++;
  for (int i = 0; i < n; i++)
    if (!isfinite(x[i]))
      return mpm_err_set(err, MPM_ENONFINITE,
                         "linalg: solution of the %d x %d system is not finite at row %d", n, n, i);
  return MPM_OK;
}
