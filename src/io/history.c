/* history.c (io): velocity-gradient histories as CSV: the reader, with
 * line-numbered errors, and the writer (io/history.h). The history itself,
 * its evaluation and the built-in [DK15] App. B table are numerical code and
 * live in pointrun/history.h.
 *
 * A row is "t, Lxx, Lxy, Lyx, Lyy"; node k of the history gets t_k = t and
 * L[4k .. 4k+3] = (Lxx, Lxy, Lyx, Lyy). Numbers are written with %.17g, so
 * writing and reading back gives the same doubles. */
#define _POSIX_C_SOURCE 200809L
#include "io/history.h"

#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "io/text.h"

static const char *const col_names[MPM_HISTORY_NCOL] = {"t", "Lxx", "Lxy", "Lyx", "Lyy"};

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
    field[n++] = mpm_io_text_trim(s);
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
  mpm_history *h = mpm_pointrun_history_alloc(r->n);
  if (!h)
    return mpm_err_set(err, MPM_ENOMEM, "%s: out of memory", name);
  for (size_t k = 0; k < r->n; k++) {
    h->t[k] = r->v[k * MPM_HISTORY_NCOL];
    memcpy(h->L + 4 * k, r->v + k * MPM_HISTORY_NCOL + 1, 4 * sizeof(double));
  }
  *out = h;
  return MPM_OK;
}

int mpm_io_history_parse(FILE *f, const char *name, mpm_history **out, mpm_err *err)
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
    char *text = mpm_io_text_trim(line);
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

int mpm_io_history_read(const char *path, mpm_history **out, mpm_err *err)
{
  if (strcmp(path, "-") == 0)
    return mpm_io_history_parse(stdin, "<stdin>", out, err);
  FILE *f = fopen(path, "r");
  if (!f) {
    *out = NULL;
    return mpm_err_set(err, MPM_EIO, "%s: cannot open: %s", path, strerror(errno));
  }
  int rc = mpm_io_history_parse(f, path, out, err);
  fclose(f);
  return rc;
}

int mpm_io_history_write(FILE *f, const mpm_history *h)
{
  fprintf(f, "t,Lxx,Lxy,Lyx,Lyy\n");
  for (size_t k = 0; k < h->n; k++) {
    const double *L = h->L + 4 * k;
    fprintf(f, "%.17g,%.17g,%.17g,%.17g,%.17g\n", h->t[k], L[0], L[1], L[2], L[3]);
  }
  return ferror(f) ? MPM_EIO : MPM_OK;
}
