/* state.c: `granmpm state`: nodal density of one output frame projected back
 * to the points ([DK15] section 4.3, Fig. 7). The mesh comes from the input
 * file the run was made with; the points from the run's frame. */
#define _POSIX_C_SOURCE 200809L
#include "app/state.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "diag/region.h"
#include "io/io.h"

enum { EXIT_USAGE_ = 2 };

static int fail(const char *msg)
{
  fprintf(stderr, "granmpm: %s\n", msg);
  return EXIT_USAGE_;
}

/* Points of the CSV text "x,y,mass\n..." (header first) into arrays. */
static int parse_points(char *text, size_t *n, double **x, double **y, double **m)
{
  size_t cap = 0;
  *n = 0;
  *x = *y = *m = NULL;
  char *line = strchr(text, '\n');          /* skip the header */
  while (line && *++line) {
    double a, b, c;
    if (sscanf(line, "%lf,%lf,%lf", &a, &b, &c) != 3)
      return 0;
    if (*n == cap) {
      cap = cap ? 2 * cap : 1024;
      double *nx = realloc(*x, cap * sizeof *nx);
      if (nx) *x = nx;
      double *ny = realloc(*y, cap * sizeof *ny);
      if (ny) *y = ny;
      double *nm = realloc(*m, cap * sizeof *nm);
      if (nm) *m = nm;
      if (!nx || !ny || !nm)
        return 0;
    }
    (*x)[*n] = a;
    (*y)[*n] = b;
    (*m)[(*n)++] = c;
    line = strchr(line, '\n');
  }
  return 1;
}

int mpm_app_state(int argc, char **argv)
{
  const char *input = NULL, *dir = NULL;
  int frame = -1;
  for (int i = 1; i < argc; i++) {
    if (strcmp(argv[i], "--frame") == 0 && i + 1 < argc) {
      const char *v = argv[++i];
      char *end;
      long f = strtol(v, &end, 10);
      if (strcmp(v, "last") == 0)
        frame = -1;
      else if (*v && !*end && f >= 0 && f <= 1000000000L)
        frame = (int)f;
      else
        return fail("state: --frame expects a frame number >= 0 or 'last'");
    } else if (argv[i][0] == '-') {
      return fail("state: usage: granmpm state INPUT RUNDIR [--frame N|last]");
    } else if (!input) {
      input = argv[i];
    } else if (!dir) {
      dir = argv[i];
    } else {
      return fail("state: usage: granmpm state INPUT RUNDIR [--frame N|last]");
    }
  }
  if (!input || !dir)
    return fail("state: usage: granmpm state INPUT RUNDIR [--frame N|last]");
  mpm_config cfg;
  mpm_err err = {0};
  if (mpm_input_load(input, NULL, 0, &cfg, &err) != MPM_OK)
    return fail(err.msg);
  mpm_mesh m;
  if (mpm_mesh_from_config(&m, &cfg, &err) != MPM_OK)
    return fail(err.msg);
  char *text = NULL;
  size_t len = 0;
  FILE *f = open_memstream(&text, &len);
  if (!f)
    return fail("state: out of memory");
  int rc = mpm_extract(dir, frame, "x,y,mass", f, &err);
  fclose(f);
  if (rc != MPM_OK) {
    free(text);
    return fail(err.msg);
  }
  size_t n = 0;
  double *x = NULL, *y = NULL, *mass = NULL, *rho = NULL;
  int ok = parse_points(text, &n, &x, &y, &mass);
  free(text);
  if (ok && n > 0 && !(rho = malloc(n * sizeof *rho)))
    ok = 0;
  if (ok && n > 0 && mpm_diag_nodal_density(&m, n, x, y, mass, rho, &err) != MPM_OK) {
    fprintf(stderr, "granmpm: %s\n", err.msg);
    ok = -1;
  }
  if (ok == 1) {
    puts("x,y,rho_nodal,state_nodal");
    for (size_t p = 0; p < n; p++)
      printf("%.10g,%.10g,%.10g,%d\n", x[p], y[p], rho[p], rho[p] < cfg.material.rho_c);
  } else if (ok == 0) {
    fprintf(stderr, "granmpm: state: cannot read the points of %s\n", dir);
  }
  free(x);
  free(y);
  free(mass);
  free(rho);
  return ok == 1 ? 0 : 1;
}
