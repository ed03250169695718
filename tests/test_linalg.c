/* test_linalg.c: the sparse symmetric solver corner (src/linalg). From the
 * definitions: x solves A x = b (residual at round-off) for an SPD matrix
 * given by one triangle in mixed order with duplicates summed; the analysis
 * and the factorisation are done only when asked, and counted; a symmetric
 * matrix that is not positive definite but regular is solved through the
 * QR fallback, which is reported with the column where Cholesky stopped; a
 * singular matrix (exactly, or the singular 1D Neumann Laplacian) and an
 * empty or non-finite system are errors that name the size, never a crash. */
#include <check.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "linalg/linalg.h"

/* Triplets of a symmetric matrix, at most cap entries. */
typedef struct trip {
  size_t n, cap;
  int *r, *c;
  double *v;
} trip;

static trip trip_new(size_t cap)
{
  trip t = {0, cap, malloc(cap * sizeof(int)), malloc(cap * sizeof(int)),
            malloc(cap * sizeof(double))};
  return t;
}

static void trip_add(trip *t, int r, int c, double v)
{
  ck_assert(t->n < t->cap);
  t->r[t->n] = r;
  t->c[t->n] = c;
  t->v[t->n] = v;
  t->n++;
}

static void trip_free(trip *t)
{
  free(t->r);
  free(t->c);
  free(t->v);
}

/* y = A x for the symmetric matrix of t (each off-diagonal entry counts twice). */
static void trip_mul(const trip *t, int n, const double *x, double *y)
{
  for (int i = 0; i < n; i++)
    y[i] = 0.0;
  for (size_t k = 0; k < t->n; k++) {
    y[t->r[k]] += t->v[k] * x[t->c[k]];
    if (t->r[k] != t->c[k])
      y[t->c[k]] += t->v[k] * x[t->r[k]];
  }
}

/* max |A x - b| / (max |A| max |x| + max |b|) */
static double rel_residual(const trip *t, int n, const double *x, const double *b)
{
  double *y = malloc((size_t)n * sizeof *y);
  trip_mul(t, n, x, y);
  double r = 0.0, xm = 0.0, bm = 0.0, am = 0.0;
  for (int i = 0; i < n; i++) {
    r = fmax(r, fabs(y[i] - b[i]));
    xm = fmax(xm, fabs(x[i]));
    bm = fmax(bm, fabs(b[i]));
  }
  for (size_t k = 0; k < t->n; k++)
    am = fmax(am, fabs(t->v[k]));
  free(y);
  return r / (am * xm + bm);
}

/* 2D 5-point operator 4 + s on an m x m grid (SPD for s > 0), upper and
 * lower entries mixed, the diagonal split into two duplicates. */
static trip grid_matrix(int m, double s)
{
  trip t = trip_new((size_t)m * m * 4);
  for (int j = 0; j < m; j++)
    for (int i = 0; i < m; i++) {
      int e = i + m * j;
      trip_add(&t, e, e, 1.0 + s);
      trip_add(&t, e, e, 3.0);
      if (i + 1 < m)
        ((i + j) % 2 ? trip_add(&t, e, e + 1, -1.0) : trip_add(&t, e + 1, e, -1.0));
      if (j + 1 < m)
        trip_add(&t, e + m, e, -1.0);
    }
  return t;
}

START_TEST(t_spd_solve)
{
  const int m = 7, n = m * m;
  trip t = grid_matrix(m, 0.3);
  double *b = malloc(n * sizeof *b), *x = malloc(n * sizeof *x);
  for (int i = 0; i < n; i++)
    b[i] = sin(1.0 + 0.7 * i);
  mpm_err err = {0};
  mpm_linalg_spd *s = mpm_linalg_spd_alloc(&err);
  ck_assert_ptr_nonnull(s);
  ck_assert_int_eq(mpm_linalg_spd_set(s, n, t.n, t.r, t.c, t.v, &err), MPM_OK);
  ck_assert_int_eq(mpm_linalg_spd_analyse(s, &err), MPM_OK);
  ck_assert_int_eq(mpm_linalg_spd_factor(s, &err), MPM_OK);
  ck_assert_int_eq(mpm_linalg_spd_solve(s, b, x, &err), MPM_OK);
  double r = rel_residual(&t, n, x, b);
  ck_assert_msg(r < 10 * DBL_EPSILON, "relative residual %g", r);
  memcpy(x, b, n * sizeof *x);               /* in place */
  ck_assert_int_eq(mpm_linalg_spd_solve(s, x, x, &err), MPM_OK);
  ck_assert(rel_residual(&t, n, x, b) < 10 * DBL_EPSILON);
  mpm_linalg_stats st = mpm_linalg_spd_stats(s);
  ck_assert_int_eq(st.n, n);
  ck_assert_int_eq(st.analyses, 1);
  ck_assert_int_eq(st.factors, 1);
  ck_assert_int_eq(st.solves, 2);
  ck_assert_int_eq(st.fallback, 0);
  ck_assert_int_eq(st.failed_col, -1);
  mpm_linalg_spd_free(s);
  trip_free(&t);
  free(b);
  free(x);
}
END_TEST

/* Same pattern, new values: factor again without an analysis; new pattern:
 * factor refuses until analysed. */
START_TEST(t_reuse_counts)
{
  const int m = 5, n = m * m;
  trip t1 = grid_matrix(m, 0.5), t2 = grid_matrix(m, 2.0), t3 = grid_matrix(m + 1, 0.5);
  double *b = malloc((m + 1) * (m + 1) * sizeof *b), *x = malloc((m + 1) * (m + 1) * sizeof *x);
  for (int i = 0; i < (m + 1) * (m + 1); i++)
    b[i] = cos(0.3 * i);
  mpm_err err = {0};
  mpm_linalg_spd *s = mpm_linalg_spd_alloc(&err);
  ck_assert_int_eq(mpm_linalg_spd_set(s, n, t1.n, t1.r, t1.c, t1.v, &err), MPM_OK);
  ck_assert_int_eq(mpm_linalg_spd_analyse(s, &err), MPM_OK);
  ck_assert_int_eq(mpm_linalg_spd_factor(s, &err), MPM_OK);
  for (int k = 0; k < 3; k++)
    ck_assert_int_eq(mpm_linalg_spd_solve(s, b, x, &err), MPM_OK);
  ck_assert(rel_residual(&t1, n, x, b) < 10 * DBL_EPSILON);
  ck_assert_int_eq(mpm_linalg_spd_set(s, n, t2.n, t2.r, t2.c, t2.v, &err), MPM_OK);
  ck_assert_int_eq(mpm_linalg_spd_solve(s, b, x, &err), MPM_EINVAL);  /* stale factor */
  ck_assert_int_eq(mpm_linalg_spd_factor(s, &err), MPM_OK);
  ck_assert_int_eq(mpm_linalg_spd_solve(s, b, x, &err), MPM_OK);
  ck_assert(rel_residual(&t2, n, x, b) < 10 * DBL_EPSILON);
  mpm_linalg_stats st = mpm_linalg_spd_stats(s);
  ck_assert_int_eq(st.analyses, 1);
  ck_assert_int_eq(st.factors, 2);
  ck_assert_int_eq(st.solves, 4);
  const int n3 = (m + 1) * (m + 1);
  ck_assert_int_eq(mpm_linalg_spd_set(s, n3, t3.n, t3.r, t3.c, t3.v, &err), MPM_OK);
  ck_assert_int_eq(mpm_linalg_spd_factor(s, &err), MPM_EINVAL);  /* pattern not analysed */
  ck_assert_int_eq(mpm_linalg_spd_analyse(s, &err), MPM_OK);
  ck_assert_int_eq(mpm_linalg_spd_factor(s, &err), MPM_OK);
  ck_assert_int_eq(mpm_linalg_spd_solve(s, b, x, &err), MPM_OK);
  ck_assert(rel_residual(&t3, n3, x, b) < 10 * DBL_EPSILON);
  st = mpm_linalg_spd_stats(s);
  ck_assert_int_eq(st.analyses, 2);
  ck_assert_int_eq(st.factors, 3);
  mpm_linalg_spd_free(s);
  trip_free(&t1);
  trip_free(&t2);
  trip_free(&t3);
  free(b);
  free(x);
}
END_TEST

/* Symmetric, regular, indefinite: Cholesky stops, QR solves, the flag says
 * so; SPD values on the same pattern afterwards go back to Cholesky. */
START_TEST(t_indefinite_fallback)
{
  const int m = 4, n = m * m;
  trip t = grid_matrix(m, 0.5);
  for (size_t k = 0; k < t.n; k++)
    if (t.r[k] == t.c[k] && t.r[k] == 9 && t.v[k] == 3.0)
      t.v[k] = -9.0;                         /* a_99 = 1.5 - 9 < 0 */
  double b[16], x[16];
  for (int i = 0; i < n; i++)
    b[i] = 1.0 + 0.1 * i;
  mpm_err err = {0};
  mpm_linalg_spd *s = mpm_linalg_spd_alloc(&err);
  ck_assert_int_eq(mpm_linalg_spd_set(s, n, t.n, t.r, t.c, t.v, &err), MPM_OK);
  ck_assert_int_eq(mpm_linalg_spd_analyse(s, &err), MPM_OK);
  ck_assert_int_eq(mpm_linalg_spd_factor(s, &err), MPM_OK);
  mpm_linalg_stats st = mpm_linalg_spd_stats(s);
  ck_assert_int_eq(st.fallback, 1);
  ck_assert_int_eq(st.fallbacks, 1);
  ck_assert(st.failed_col >= 0 && st.failed_col < n);
  ck_assert_int_eq(mpm_linalg_spd_solve(s, b, x, &err), MPM_OK);
  double r = rel_residual(&t, n, x, b);
  ck_assert_msg(r < 10 * DBL_EPSILON, "QR relative residual %g", r);
  trip_free(&t);
  t = grid_matrix(m, 0.5);
  ck_assert_int_eq(mpm_linalg_spd_set(s, n, t.n, t.r, t.c, t.v, &err), MPM_OK);
  ck_assert_int_eq(mpm_linalg_spd_factor(s, &err), MPM_OK);
  st = mpm_linalg_spd_stats(s);
  ck_assert_int_eq(st.fallback, 0);
  ck_assert_int_eq(st.failed_col, -1);
  ck_assert_int_eq(st.analyses, 1);
  ck_assert_int_eq(st.factors, 2);
  ck_assert_int_eq(mpm_linalg_spd_solve(s, b, x, &err), MPM_OK);
  ck_assert(rel_residual(&t, n, x, b) < 10 * DBL_EPSILON);
  mpm_linalg_spd_free(s);
  trip_free(&t);
}
END_TEST

/* Factor a singular matrix: an error naming the size and a column. */
static void expect_singular(int n, const trip *t)
{
  mpm_err err = {0};
  mpm_linalg_spd *s = mpm_linalg_spd_alloc(&err);
  ck_assert_int_eq(mpm_linalg_spd_set(s, n, t->n, t->r, t->c, t->v, &err), MPM_OK);
  ck_assert_int_eq(mpm_linalg_spd_analyse(s, &err), MPM_OK);
  ck_assert_int_eq(mpm_linalg_spd_factor(s, &err), MPM_ESOLVE);
  char size[32];
  snprintf(size, sizeof size, "%d x %d", n, n);
  ck_assert_msg(strstr(err.msg, size) && strstr(err.msg, "column"), "message: %s", err.msg);
  double b[8] = {1, 1, 1, 1, 1, 1, 1, 1}, x[8];
  ck_assert_int_eq(mpm_linalg_spd_solve(s, b, x, &err), MPM_EINVAL);
  mpm_linalg_spd_free(s);
}

START_TEST(t_singular)
{
  trip t = trip_new(8);
  trip_add(&t, 0, 0, 1.0);                   /* [1 1; 1 1] */
  trip_add(&t, 1, 0, 1.0);
  trip_add(&t, 1, 1, 1.0);
  expect_singular(2, &t);
  trip_free(&t);
  t = trip_new(8);
  trip_add(&t, 0, 0, 2.0);                   /* row 1 missing: zero row and column */
  trip_add(&t, 2, 2, 2.0);
  expect_singular(3, &t);
  trip_free(&t);
  const int n = 6;                           /* 1D Neumann Laplacian: constants in its kernel */
  t = trip_new(2 * n);
  for (int i = 0; i < n; i++) {
    trip_add(&t, i, i, (i == 0 || i == n - 1) ? 1.0 : 2.0);
    if (i + 1 < n)
      trip_add(&t, i, i + 1, -1.0);
  }
  expect_singular(n, &t);
  trip_free(&t);
}
END_TEST

START_TEST(t_bad_input)
{
  mpm_err err = {0};
  mpm_linalg_spd *s = mpm_linalg_spd_alloc(&err);
  int r[2] = {0, 1}, c[2] = {0, 3};
  double v[2] = {1.0, NAN};
  ck_assert_int_eq(mpm_linalg_spd_set(s, 0, 0, r, c, v, &err), MPM_EINVAL);   /* empty */
  ck_assert_ptr_nonnull(strstr(err.msg, "empty"));
  ck_assert_int_eq(mpm_linalg_spd_set(s, 2, 2, r, c, v, &err), MPM_EINVAL);   /* (1, 3) */
  c[1] = 1;
  ck_assert_int_eq(mpm_linalg_spd_set(s, 2, 2, r, c, v, &err), MPM_EINVAL);   /* NaN */
  ck_assert_int_eq(mpm_linalg_spd_analyse(s, &err), MPM_EINVAL);  /* no matrix */
  ck_assert_int_eq(mpm_linalg_spd_factor(s, &err), MPM_EINVAL);
  double b[2] = {1, 1}, x[2];
  ck_assert_int_eq(mpm_linalg_spd_solve(s, b, x, &err), MPM_EINVAL);
  mpm_linalg_stats st = mpm_linalg_spd_stats(s);
  ck_assert_int_eq(st.analyses + st.factors + st.solves, 0);
  mpm_linalg_spd_free(s);
  mpm_linalg_spd_free(NULL);
}
END_TEST

static Suite *suite(void)
{
  Suite *s = suite_create("linalg");
  TCase *tc = tcase_create("spd");
  tcase_add_test(tc, t_spd_solve);
  tcase_add_test(tc, t_reuse_counts);
  tcase_add_test(tc, t_indefinite_fallback);
  tcase_add_test(tc, t_singular);
  tcase_add_test(tc, t_bad_input);
  suite_add_tcase(s, tc);
  return s;
}

int main(void)
{
  SRunner *sr = srunner_create(suite());
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
