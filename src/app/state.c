/* state.c: `granmpm state`: nodal density of one output frame projected back
 * to the points ([DK15] section 4.3, Fig. 7). The mesh comes from the input
 * file the run was made with; the points from the run's frame (io/frame.c),
 * the density from diag/region.c. */
#include "app/state.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/args.h"
#include "diag/region.h"
#include "io/io.h"

static const char usage_line[] = "state: usage: granmpm state INPUT RUNDIR [--frame N|last]";

/* The points of frame `frame` of run dir, and the mesh and rho_c of input. */
static int load(const char *input, const char *dir, int frame, mpm_config *cfg, mpm_mesh *m,
                mpm_points *pts, mpm_err *err)
{
  mpm_io_run *r = NULL;
  double t;
  int rc = mpm_io_input_load(input, NULL, 0, cfg, err);
  if (rc == MPM_OK)
    rc = mpm_mesh_from_config(m, cfg, err);
  if (rc == MPM_OK)
    rc = mpm_io_run_open(&r, dir, err);
  if (rc == MPM_OK)
    rc = mpm_io_run_frame(r, frame, pts, &t, err);
  mpm_io_run_close(r);
  return rc;
}

int mpm_app_state(int argc, char **argv)
{
  const char *pos[2] = {NULL, NULL}; /* INPUT RUNDIR */
  int frame = -1;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    int st;
    if (strcmp(a, "--frame") == 0 && v) {
      st = mpm_app_arg_frame("state", v, &frame);
      i++;
    } else if (a[0] == '-' && a[1] != '\0') {
      st = mpm_app_usage("%s", usage_line);
    } else {
      st = mpm_app_arg_positional("state", a, pos, 2);
    }
    if (st != 0)
      return st;
  }
  if (!pos[1])
    return mpm_app_usage("%s", usage_line);
  mpm_config cfg;
  mpm_mesh m;
  mpm_err err = {0};
  mpm_points *pts = mpm_points_alloc(0);
  double *rho = NULL;
  int rc = pts ? load(pos[0], pos[1], frame, &cfg, &m, pts, &err)
               : mpm_err_set(&err, MPM_ENOMEM, "state: out of memory");
  if (rc == MPM_OK && pts->n > 0 && !(rho = malloc(pts->n * sizeof *rho)))
    rc = mpm_err_set(&err, MPM_ENOMEM, "state: out of memory");
  if (rc == MPM_OK && pts->n > 0)
    rc = mpm_diag_nodal_density(&m, pts, rho, &err);
  if (rc == MPM_OK) {
    puts("x,y,rho_nodal,state_nodal");
    for (size_t p = 0; p < pts->n; p++)
      printf("%.10g,%.10g,%.10g,%d\n", pts->x[p], pts->y[p], rho[p], rho[p] < cfg.material.rho_c);
  }
  free(rho);
  mpm_points_free(pts);
  if (rc != MPM_OK)
    return mpm_app_fail(&err);
  return fflush(stdout) == 0 ? 0 : MPM_APP_EXIT_RUNTIME;
}
