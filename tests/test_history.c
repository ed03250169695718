/* test_history.c: velocity-gradient histories: the [DK15] App. B table against
 * eq. B1-B2, linear evaluation and exact step means, and the CSV reader and
 * writer of io/ (accepted forms, line-numbered errors, round trip, trim). */
#define _POSIX_C_SOURCE 200809L
#include <check.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/history.h"
#include "io/text.h"
#include "pointrun/history.h"

/* eq. B1-B2 evaluated directly: Lxx = Lyy = [H(t-.25) - H(t-.5)] (|8t-3| - 1)
 * + [H(t-.75) - H(t-1)] (1 - |8t-7|), Lxy = 0.05. */
static double dk15_Lxx(double t)
{
  double com = (t >= 0.25 && t < 0.5) ? fabs(8.0 * t - 3.0) - 1.0 : 0.0;
  double ext = (t >= 0.75 && t < 1.0) ? 1.0 - fabs(8.0 * t - 7.0) : 0.0;
  return com + ext;
}

static mpm_history *parse_text(const char *text, mpm_err *err, int *rc)
{
  FILE *f = fmemopen((void *)text, strlen(text), "r");
  ck_assert_ptr_nonnull(f);
  mpm_history *h = NULL;
  *rc = mpm_io_history_parse(f, "h.csv", &h, err);
  fclose(f);
  return h;
}

START_TEST(t_dk15_matches_formula)
{
  mpm_err err = {0};
  mpm_history *h = NULL;
  ck_assert_int_eq(mpm_pointrun_history_dk15(&h, &err), MPM_OK);
  ck_assert_double_eq(mpm_pointrun_history_t_begin(h), 0.0);
  ck_assert_double_eq(mpm_pointrun_history_t_end(h), 1.25);
  for (int i = 0; i <= 12500; i++) {
    double t = 1.25 * i / 12500.0;
    mpm_mat3 L = mpm_pointrun_history_eval(h, t);
    /* linear interpolation of exact binary nodes: a few roundings */
    ck_assert_double_eq_tol(L.m[0][0], dk15_Lxx(t), 1e-14);
    ck_assert_double_eq_tol(L.m[1][1], dk15_Lxx(t), 1e-14);
    ck_assert_double_eq_tol(L.m[0][1], 0.05, 1e-16);
    ck_assert_double_eq(L.m[1][0], 0.0);
    ck_assert_double_eq(L.m[2][2], 0.0);
  }
  mpm_pointrun_history_free(h);
}
END_TEST

/* Step means are exact integrals of the piecewise-linear L. */
START_TEST(t_mean_exact)
{
  mpm_err err = {0};
  mpm_history *h = NULL;
  ck_assert_int_eq(mpm_pointrun_history_dk15(&h, &err), MPM_OK);
  /* compression phase: int_0.25^0.5 Lxx = -1/8 (triangle of base 1/4, height 1) */
  mpm_mat3 M = mpm_pointrun_history_mean(h, 0.25, 0.5);
  ck_assert_double_eq_tol(M.m[0][0] * 0.25, -0.125, 1e-16);
  /* whole history: compression and extension cancel */
  M = mpm_pointrun_history_mean(h, 0.0, 1.25);
  ck_assert_double_eq_tol(M.m[0][0], 0.0, 1e-16);
  ck_assert_double_eq_tol(M.m[0][1], 0.05, 1e-16);
  /* across the kink at 3/8: int_0.3^0.45 (|8t-3| - 1) dt by hand:
   * [0.3,0.375]: 2t - 4t^2 -> (0.75 - 0.5625) - (0.6 - 0.36) = -0.0525;
   * [0.375,0.45]: 4t^2 - 4t -> (0.81 - 1.8) - (0.5625 - 1.5) = -0.0525. */
  M = mpm_pointrun_history_mean(h, 0.3, 0.45);
  ck_assert_double_eq_tol(M.m[0][0] * 0.15, -0.105, 1e-15);
  /* a step that straddles nothing equals the value at its midpoint */
  M = mpm_pointrun_history_mean(h, 0.26, 0.27);
  ck_assert_double_eq_tol(M.m[0][0], dk15_Lxx(0.265), 1e-14);
  /* beyond the table: constant extension */
  M = mpm_pointrun_history_mean(h, 1.25, 1.5);
  ck_assert_double_eq_tol(M.m[0][1], 0.05, 1e-16);
  ck_assert_double_eq(M.m[0][0], 0.0);
  mpm_pointrun_history_free(h);
}
END_TEST

START_TEST(t_segment_lookup)
{
  mpm_err err = {0};
  mpm_history *h = NULL;
  ck_assert_int_eq(mpm_pointrun_history_dk15(&h, &err), MPM_OK);
  ck_assert_uint_eq(mpm_pointrun_history_segment(h, -1.0), 0);
  ck_assert_uint_eq(mpm_pointrun_history_segment(h, 0.0), 0);
  ck_assert_uint_eq(mpm_pointrun_history_segment(h, 0.25), 1);   /* a node starts its segment */
  ck_assert_uint_eq(mpm_pointrun_history_segment(h, 0.3), 1);
  ck_assert_uint_eq(mpm_pointrun_history_segment(h, 0.375), 2);
  ck_assert_uint_eq(mpm_pointrun_history_segment(h, 1.25), 6);   /* last node: last segment */
  ck_assert_uint_eq(mpm_pointrun_history_segment(h, 9.0), 6);
  mpm_pointrun_history_free(h);
}
END_TEST

START_TEST(t_parse_accepts)
{
  const char *text =
    "# a history\r\n"
    " t , Lxx, Lxy , Lyx, Lyy   # header, spaces and CRLF allowed\r\n"
    "\n"
    "0, 0, 0.1, 0, 0\n"
    "0.5,-1e-1,0.1,0x1p-3,  2.5  # trailing comment\n"
    "   \n"
    "1.5, 0, 0, 0, 0\n";
  mpm_err err = {0};
  int rc;
  mpm_history *h = parse_text(text, &err, &rc);
  ck_assert_msg(rc == MPM_OK, "%s", err.msg);
  ck_assert_uint_eq(h->n, 3);
  ck_assert_double_eq(h->t[1], 0.5);
  ck_assert_double_eq(h->L[4 + 0], -0.1);
  ck_assert_double_eq(h->L[4 + 2], 0.125);
  ck_assert_double_eq(h->L[4 + 3], 2.5);
  mpm_mat3 L = mpm_pointrun_history_eval(h, 1.0);  /* halfway along segment 1 */
  ck_assert_double_eq_tol(L.m[0][0], -0.05, 1e-16);
  ck_assert_double_eq_tol(L.m[1][1], 1.25, 1e-15);
  /* no header: the first row is data */
  mpm_pointrun_history_free(h);
  h = parse_text("0,1,2,3,4\n1,1,2,3,4\n", &err, &rc);
  ck_assert_int_eq(rc, MPM_OK);
  ck_assert_double_eq(h->L[3], 4.0);
  mpm_pointrun_history_free(h);
}
END_TEST

/* Round trip through the writer. */
START_TEST(t_write_parse_roundtrip)
{
  mpm_err err = {0};
  mpm_history *h = NULL, *g = NULL;
  ck_assert_int_eq(mpm_pointrun_history_dk15(&h, &err), MPM_OK);
  char *buf = NULL;
  size_t len = 0;
  FILE *f = open_memstream(&buf, &len);
  ck_assert_int_eq(mpm_io_history_write(f, h), MPM_OK);
  fclose(f);
  int rc;
  g = parse_text(buf, &err, &rc);
  ck_assert_int_eq(rc, MPM_OK);
  ck_assert_uint_eq(g->n, h->n);
  ck_assert_mem_eq(g->t, h->t, h->n * sizeof(double));
  ck_assert_mem_eq(g->L, h->L, 4 * h->n * sizeof(double));
  free(buf);
  mpm_pointrun_history_free(h);
  mpm_pointrun_history_free(g);
}
END_TEST

START_TEST(t_parse_errors)
{
  struct { const char *text, *msg; } cases[] = {
    {"t,Lxx,Lxy,Lyx,Lyy\n0,0,0,0,0\n1,0,0,0\n",
     "h.csv:3: expected 5 numbers (t, Lxx, Lxy, Lyx, Lyy), got 4"},
    {"0,0,0,0,0\n1,0,0,0,0,7\n", "h.csv:2: expected 5 numbers (t, Lxx, Lxy, Lyx, Lyy), got more than 5"},
    {"0,0,0,0,0\n1,0,abc,0,0\n", "h.csv:2: column 3 (Lxy): 'abc' is not a finite number"},
    {"0,0,0,0,0\n1,0,,0,0\n", "h.csv:2: column 3 (Lxy): '' is not a finite number"},
    {"0,0,0,0,0\n1,0,nan,0,0\n", "h.csv:2: column 3 (Lxy): 'nan' is not a finite number"},
    {"0,0,0,0,0\n1,inf,0,0,0\n", "h.csv:2: column 2 (Lxx): 'inf' is not a finite number"},
    {"0,0,0,0,0\n1e999,0,0,0,0\n", "h.csv:2: column 1 (t): '1e999' is not a finite number"},
    {"# c\n0,0,0,0,0\n\n0.5,0,0,0,0\n0.5,0,0,0,0\n",
     "h.csv:5: t = 0.5 is not after t = 0.5 on line 4 (times must strictly increase)"},
    {"0,0,0,0,0\n-1,0,0,0,0\n", "h.csv:2: t = -1 is not after t = 0 on line 1"},
    {"time,Lxx,Lxy,Lyx,Lyy\n0,0,0,0,0\n1,0,0,0,0\n",
     "h.csv:1: 'time' is neither the header 't,Lxx,Lxy,Lyx,Lyy' nor a row of 5 numbers"},
    {"0,0,0,0,0\nt,Lxx,Lxy,Lyx,Lyy\n", "h.csv:2: column 1 (t): 't' is not a finite number"},
    {"t,Lxx,Lxy,Lyx,Lyy\n0,0,0,0,0\n", "h.csv: 1 data row; a history needs at least 2 rows"},
    {"", "h.csv: 0 data rows; a history needs at least 2 rows"},
    {"0;0;0;0;0\n1;0;0;0;0\n", "h.csv:1: '0;0;0;0;0' is neither the header"},
  };
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
    mpm_err err = {0};
    int rc;
    mpm_history *h = parse_text(cases[i].text, &err, &rc);
    ck_assert_int_eq(rc, MPM_EINPUT);
    ck_assert_ptr_null(h);
    ck_assert_msg(strncmp(err.msg, cases[i].msg, strlen(cases[i].msg)) == 0,
                  "case %zu: got '%s', expected '%s...'", i, err.msg, cases[i].msg);
  }
}
END_TEST

START_TEST(t_read_missing_file)
{
  mpm_err err = {0};
  mpm_history *h = NULL;
  ck_assert_int_eq(mpm_io_history_read("/nonexistent/dir/h.csv", &h, &err), MPM_EIO);
  ck_assert_ptr_null(h);
  ck_assert_ptr_nonnull(strstr(err.msg, "/nonexistent/dir/h.csv: cannot open"));
}
END_TEST

/* The reader's trim: leading blanks skipped, trailing ones cut in place. */
START_TEST(t_text_trim)
{
  char a[] = " \t x, y \r\n", b[] = "   ", c[] = "z";
  char *s = mpm_io_text_trim(a);
  ck_assert_str_eq(s, "x, y");
  ck_assert_ptr_eq(s, a + 3);
  ck_assert_str_eq(mpm_io_text_trim(b), "");
  ck_assert_ptr_eq(mpm_io_text_trim(c), c);
  ck_assert_str_eq(c, "z");
}
END_TEST

int main(void)
{
  Suite *s = suite_create("history");
  TCase *tc = tcase_create("history");
  tcase_add_test(tc, t_dk15_matches_formula);
  tcase_add_test(tc, t_mean_exact);
  tcase_add_test(tc, t_segment_lookup);
  tcase_add_test(tc, t_parse_accepts);
  tcase_add_test(tc, t_write_parse_roundtrip);
  tcase_add_test(tc, t_parse_errors);
  tcase_add_test(tc, t_read_missing_file);
  tcase_add_test(tc, t_text_trim);
  suite_add_tcase(s, tc);
  SRunner *sr = srunner_create(s);
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf ? EXIT_FAILURE : EXIT_SUCCESS;
}
