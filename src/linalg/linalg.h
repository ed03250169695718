/* linalg.h: sparse symmetric positive definite systems A x = b, the only
 * code that talks to SuiteSparse (CHOLMOD, with a CSparse QR as the
 * fallback, as [D-thesis] section 3.5.2 does).
 *
 * A is n x n, symmetric, given as triplets (row, column, value) of ONE
 * triangle (lower or upper, mixed freely: an entry (i, j) stands for both
 * (i, j) and (j, i)); duplicates are summed. The three phases are separate
 * so that callers redo only what changed:
 *   mpm_linalg_spd_set      the matrix (pattern and values);
 *   mpm_linalg_spd_analyse  AMD ordering and symbolic factorisation, only
 *                           when the pattern changed;
 *   mpm_linalg_spd_factor   numeric factorisation, only when values changed;
 *   mpm_linalg_spd_solve    x = A^-1 b, as often as needed.
 * The Cholesky factor is simplicial LL' (no BLAS, so results do not depend
 * on the thread count of a BLAS library). If A is not positive definite,
 * CHOLMOD stops at a column; the factorisation then falls back to a CSparse
 * Householder QR of the full matrix and reports it in
 * mpm_linalg_stats.fallback. If R has a zero or negligible diagonal entry
 * (|r_jj| <= n eps max_k |r_kk|) A is taken as singular: MPM_ESOLVE naming
 * the size and the column; the caller adds where and when (step, time).
 * An empty system (n = 0) or non-finite values are errors too. */
#ifndef MPM_LINALG_LINALG_H
#define MPM_LINALG_LINALG_H

#include <stddef.h>

#include "core/error.h"

typedef struct mpm_linalg_spd mpm_linalg_spd;   /* opaque */

/* Counters and state, for callers and tests. */
typedef struct mpm_linalg_stats {
  int n;              /* size of the current matrix (0: none) */
  long analyses;      /* symbolic analyses done */
  long factors;       /* numeric factorisations done (Cholesky, with or without QR) */
  long fallbacks;     /* of these, the ones that fell back to QR */
  long solves;        /* solves done */
  int fallback;       /* 1 when the current factor is the QR fallback */
  long failed_col;    /* column where the last Cholesky stopped, -1 if it did not */
} mpm_linalg_stats;

/* A new solver with no matrix; NULL (and err set) when out of memory. */
mpm_linalg_spd *mpm_linalg_spd_alloc(mpm_err *err);
void mpm_linalg_spd_free(mpm_linalg_spd *s);   /* accepts NULL */

/* Set A from nnz triplets (row[k], col[k], val[k]), 0 <= row, col < n. The
 * factor is kept: after a new pattern call _analyse, after new values
 * _factor. MPM_EINVAL for n < 1, an index out of range or a non-finite value. */
int mpm_linalg_spd_set(mpm_linalg_spd *s, int n, size_t nnz, const int *row, const int *col,
                       const double *val, mpm_err *err);

/* 1 if the current matrix's pattern is not the one last analysed (or none
 * was): the caller must call _analyse before _factor. */
int mpm_linalg_spd_pattern_changed(const mpm_linalg_spd *s);

/* AMD ordering and symbolic factorisation of the current pattern. */
int mpm_linalg_spd_analyse(mpm_linalg_spd *s, mpm_err *err);

/* Numeric factorisation of the current values (the pattern must be the one
 * analysed: MPM_EINVAL otherwise). Cholesky, else QR (see the top). */
int mpm_linalg_spd_factor(mpm_linalg_spd *s, mpm_err *err);

/* x = A^-1 b with the current factor (b and x of length n; they may be the
 * same array). MPM_EINVAL without a factor, MPM_ENONFINITE if x is not finite. */
int mpm_linalg_spd_solve(mpm_linalg_spd *s, const double *b, double *x, mpm_err *err);

/* Counters and state of s. */
mpm_linalg_stats mpm_linalg_spd_stats(const mpm_linalg_spd *s);

#endif
