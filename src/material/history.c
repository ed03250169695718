/* history.c: velocity-gradient histories: CSV reader with line-numbered
 * errors, the [DK15] App. B table (eq. B1-B2), evaluation and exact step means.
 *
 * L(t) = L_k + (t - t_k) / (t_{k+1} - t_k) (L_{k+1} - L_k) on segment k;
 * mean over [a, b] = sum over segments of (v - u) (L(u) + L(v)) / 2 / (b - a),
 * [u, v] the part of [a, b] in the segment (trapezoid rule, exact for linear L). */
#define _POSIX_C_SOURCE 200809L
#include "material/history.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static const char *const col_names[MPM_HISTORY_NCOL] = {"t", "Lxx", "Lxy", "Lyx", "Lyy"};

mpm_history *mpm_history_alloc(size_t n)
{
  mpm_history *h = calloc(1, sizeof *h);
  if (!h)
    return NULL;
  h->n = n;
  h->t = calloc(n ? n : 1, sizeof *h->t);
  h->L = calloc(n ? 4 * n : 1, sizeof *h->L);
  if (!h->t || !h->L) {
    mpm_history_free(h);
    return NULL;
  }
  return h;
}

void mpm_history_free(mpm_history *h)
{
  if (!h)
    return;
  free(h->t);
  free(h->L);
  free(h);
}

/* ------------------------------------------------------------ CSV reader */

/* Growable list of rows while reading. */
typedef struct rows {
  size_t n, cap;
  double *v;    /* MPM_HISTORY_NCOL values per row */
  long *line;   /* source line of each row */
} rows;

static int rows_push(rows *r, const double *v, long line)
{
  if (r->n == r->cap) {
    size_t cap = r->cap ? 2 * r->cap : 64;
    double *nv = realloc(r->v, cap * MPM_HISTORY_NCOL * sizeof *nv);
    if (!nv)
      return MPM_ENOMEM;
    r->v = nv;
    long *nl = realloc(r->line, cap * sizeof *nl);
    if (!nl)
      return MPM_ENOMEM;
    r->line = nl;
    r->cap = cap;
  }
  memcpy(r->v + r->n * MPM_HISTORY_NCOL, v, MPM_HISTORY_NCOL * sizeof *v);
  r->line[r->n++] = line;
  return MPM_OK;
}

static char *trim(char *s)
{
  while (isspace((unsigned char)*s))
    s++;
  char *e = s + strlen(s);
  while (e > s && isspace((unsigned char)e[-1]))
    *--e = '\0';
  return s;
}

/* Split line at commas into at most max fields (trimmed); returns the count,
 * max + 1 if there are more. */
static int split(char *line, char **field, int max)
{
  int n = 0;
  char *s = line;
  for (;;) {
    char *c = strchr(s, ',');
    if (c)
      *c = '\0';
    if (n == max)
      return max + 1;
    field[n++] = trim(s);
    if (!c)
      return n;
    s = c + 1;
  }
}

/* A finite number filling the whole field. */
static int parse_number(const char *s, double *v)
{
  char *end;
  errno = 0;
  *v = strtod(s, &end);
  return *s != '\0' && *end == '\0' && errno != ERANGE && isfinite(*v);
}

static int is_header(char **field, int n)
{
  if (n != MPM_HISTORY_NCOL)
    return 0;
  for (int i = 0; i < MPM_HISTORY_NCOL; i++)
    if (strcasecmp(field[i], col_names[i]) != 0)
      return 0;
  return 1;
}

/* Length-limited copy of user text for messages. */
static const char *shown(const char *s, char *buf, size_t len)
{
  snprintf(buf, len, "%s%s", s, strlen(s) >= len - 1 ? "..." : "");
  return buf;
}

/* One non-blank, non-comment line: a header (first data-like line only) or a row. */
static int parse_line(char *text, const char *name, long lineno, rows *r, int *seen,
                      mpm_err *err)
{
  char *field[MPM_HISTORY_NCOL + 1];
  char buf[48];
  double first;
  int n = split(text, field, MPM_HISTORY_NCOL);
  int first_line = !*seen;
  *seen = 1;
  if (first_line && is_header(field, n))
    return MPM_OK;
  if (first_line && !parse_number(field[0], &first))
    return mpm_err_set(err, MPM_EINPUT,
                       "%s:%ld: '%s' is neither the header 't,Lxx,Lxy,Lyx,Lyy' nor a row "
                       "of 5 numbers", name, lineno, shown(field[0], buf, sizeof buf));
  if (n != MPM_HISTORY_NCOL)
    return mpm_err_set(err, MPM_EINPUT,
                       "%s:%ld: expected 5 numbers (t, Lxx, Lxy, Lyx, Lyy), got %s%d",
                       name, lineno, n > MPM_HISTORY_NCOL ? "more than " : "",
                       n > MPM_HISTORY_NCOL ? MPM_HISTORY_NCOL : n);
  double v[MPM_HISTORY_NCOL];
  for (int i = 0; i < MPM_HISTORY_NCOL; i++)
    if (!parse_number(field[i], &v[i]))
      return mpm_err_set(err, MPM_EINPUT,
                         "%s:%ld: column %d (%s): '%s' is not a finite number",
                         name, lineno, i + 1, col_names[i], shown(field[i], buf, sizeof buf));
  if (r->n > 0) {
    double tp = r->v[(r->n - 1) * MPM_HISTORY_NCOL];
    if (!(v[0] > tp))
      return mpm_err_set(err, MPM_EINPUT,
                         "%s:%ld: t = %.17g is not after t = %.17g on line %ld "
                         "(times must strictly increase)",
                         name, lineno, v[0], tp, r->line[r->n - 1]);
  }
  return rows_push(r, v, lineno) == MPM_OK
             ? MPM_OK : mpm_err_set(err, MPM_ENOMEM, "%s:%ld: out of memory", name, lineno);
}

static int rows_to_history(const rows *r, const char *name, mpm_history **out, mpm_err *err)
{
  if (r->n < 2)
    return mpm_err_set(err, MPM_EINPUT,
                       "%s: %zu data row%s; a history needs at least 2 rows "
                       "(t, Lxx, Lxy, Lyx, Lyy)", name, r->n, r->n == 1 ? "" : "s");
  mpm_history *h = mpm_history_alloc(r->n);
  if (!h)
    return mpm_err_set(err, MPM_ENOMEM, "%s: out of memory", name);
  for (size_t k = 0; k < r->n; k++) {
    h->t[k] = r->v[k * MPM_HISTORY_NCOL];
    memcpy(h->L + 4 * k, r->v + k * MPM_HISTORY_NCOL + 1, 4 * sizeof(double));
  }
  *out = h;
  return MPM_OK;
}

int mpm_history_parse(FILE *f, const char *name, mpm_history **out, mpm_err *err)
{
  rows r = {0};
  char *line = NULL;
  size_t cap = 0;
  long lineno = 0;
  int seen = 0, rc = MPM_OK;
  *out = NULL;
  while (rc == MPM_OK && getline(&line, &cap, f) != -1) {
    lineno++;
    char *hash = strchr(line, '#');
    if (hash)
      *hash = '\0';
    char *text = trim(line);
    if (*text != '\0')
      rc = parse_line(text, name, lineno, &r, &seen, err);
  }
  if (rc == MPM_OK && ferror(f))
    rc = mpm_err_set(err, MPM_EIO, "%s:%ld: read error", name, lineno);
  if (rc == MPM_OK)
    rc = rows_to_history(&r, name, out, err);
  free(line);
  free(r.v);
  free(r.line);
  return rc;
}

int mpm_history_read(const char *path, mpm_history **out, mpm_err *err)
{
  if (strcmp(path, "-") == 0)
    return mpm_history_parse(stdin, "<stdin>", out, err);
  FILE *f = fopen(path, "r");
  if (!f) {
    *out = NULL;
    return mpm_err_set(err, MPM_EIO, "%s: cannot open: %s", path, strerror(errno));
  }
  int rc = mpm_history_parse(f, path, out, err);
  fclose(f);
  return rc;
}

int mpm_history_write(FILE *f, const mpm_history *h)
{
  fprintf(f, "t,Lxx,Lxy,Lyx,Lyy\n");
  for (size_t k = 0; k < h->n; k++) {
    const double *L = h->L + 4 * k;
    fprintf(f, "%.17g,%.17g,%.17g,%.17g,%.17g\n", h->t[k], L[0], L[1], L[2], L[3]);
  }
  return ferror(f) ? MPM_EIO : MPM_OK;
}

/* ------------------------------------------------------- [DK15] App. B */

int mpm_history_dk15(mpm_history **out, mpm_err *err)
{
  /* Nodes where the ramps of eq. B2 switch: Lxx = Lyy = -1 at t = 3/8 (L_com),
   * +1 at t = 7/8 (L_ext), 0 at the Heaviside switches; Lxy = 0.05 throughout. */
  static const double node[][MPM_HISTORY_NCOL] = {
    {0.0, 0, 0.05, 0, 0},     {0.25, 0, 0.05, 0, 0},  {0.375, -1, 0.05, 0, -1},
    {0.5, 0, 0.05, 0, 0},     {0.75, 0, 0.05, 0, 0},  {0.875, 1, 0.05, 0, 1},
    {1.0, 0, 0.05, 0, 0},     {1.25, 0, 0.05, 0, 0},
  };
  size_t n = sizeof node / sizeof node[0];
  mpm_history *h = mpm_history_alloc(n);
  if (!h)
    return mpm_err_set(err, MPM_ENOMEM, "dk15 history: out of memory");
  for (size_t k = 0; k < n; k++) {
    h->t[k] = node[k][0];
    memcpy(h->L + 4 * k, &node[k][1], 4 * sizeof(double));
  }
  *out = h;
  return MPM_OK;
}

/* ---------------------------------------------------------- evaluation */

size_t mpm_history_segment(const mpm_history *h, double t)
{
  size_t lo = 0, hi = h->n - 1;  /* invariant: answer in [lo, hi - 1] */
  while (hi - lo > 1) {
    size_t mid = lo + (hi - lo) / 2;
    if (t >= h->t[mid])
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}

/* In-plane components into a 3x3 L. */
static mpm_mat3 plane_L(double xx, double xy, double yx, double yy)
{
  return (mpm_mat3){{{xx, xy, 0.0}, {yx, yy, 0.0}, {0.0, 0.0, 0.0}}};
}

mpm_mat3 mpm_history_eval_seg(const mpm_history *h, size_t k, double t)
{
  const double *a = h->L + 4 * k, *b = a + 4;
  double w = (t - h->t[k]) / (h->t[k + 1] - h->t[k]);  /* (t - t_k) / (t_{k+1} - t_k) */
  return plane_L(a[0] + w * (b[0] - a[0]), a[1] + w * (b[1] - a[1]),
                 a[2] + w * (b[2] - a[2]), a[3] + w * (b[3] - a[3]));
}

mpm_mat3 mpm_history_eval(const mpm_history *h, double t)
{
  if (t <= h->t[0])
    return plane_L(h->L[0], h->L[1], h->L[2], h->L[3]);
  if (t >= h->t[h->n - 1]) {
    const double *e = h->L + 4 * (h->n - 1);
    return plane_L(e[0], e[1], e[2], e[3]);
  }
  return mpm_history_eval_seg(h, mpm_history_segment(h, t), t);
}

/* int_u^v L dt on segment k (trapezoid, exact for linear L), into acc. */
static void add_segment_integral(const mpm_history *h, size_t k, double u, double v,
                                 mpm_mat3 *acc)
{
  mpm_mat3 Lu = mpm_history_eval_seg(h, k, u), Lv = mpm_history_eval_seg(h, k, v);
  for (int i = 0; i < 2; i++)
    for (int j = 0; j < 2; j++)
      acc->m[i][j] += 0.5 * (v - u) * (Lu.m[i][j] + Lv.m[i][j]);
}

mpm_mat3 mpm_history_mean(const mpm_history *h, double a, double b)
{
  mpm_mat3 acc = plane_L(0, 0, 0, 0);
  double t0 = h->t[0], t1 = h->t[h->n - 1];
  if (a < t0) {  /* constant extension before the first node */
    mpm_mat3 L0 = mpm_history_eval(h, t0);
    double v = b < t0 ? b : t0;
    for (int i = 0; i < 2; i++)
      for (int j = 0; j < 2; j++)
        acc.m[i][j] += (v - a) * L0.m[i][j];
  }
  if (b > t1) {  /* constant extension after the last node */
    mpm_mat3 L1 = mpm_history_eval(h, t1);
    double u = a > t1 ? a : t1;
    for (int i = 0; i < 2; i++)
      for (int j = 0; j < 2; j++)
        acc.m[i][j] += (b - u) * L1.m[i][j];
  }
  double lo = a > t0 ? a : t0, hi = b < t1 ? b : t1;
  for (size_t k = mpm_history_segment(h, lo); lo < hi && k + 1 < h->n; k++) {
    double v = h->t[k + 1] < hi ? h->t[k + 1] : hi;
    if (v > lo)
      add_segment_integral(h, k, lo, v, &acc);
    lo = v;
  }
  for (int i = 0; i < 2; i++)
    for (int j = 0; j < 2; j++)
      acc.m[i][j] /= (b - a);
  return acc;
}
