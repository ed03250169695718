/* plan.h: what `check`, `run` and `resume` do before the first step, the
 * same code for all three so that they never disagree: the input loaded
 * and checked, the run's size estimated and weighed against the machine
 * (available memory, free space where the output goes), the time step
 * against the stable one, the output directory tried as the run will write
 * it, and the simulation built (the fills included).
 * Every error at this stage names the file, line and key. */
#ifndef MPM_APP_PLAN_H
#define MPM_APP_PLAN_H

#include <stdio.h>

#include "core/config.h"
#include "io/io.h"
#include "solver/solver.h"

typedef struct mpm_app_plan {
  const char *file;     /* the input's name in messages */
  mpm_config cfg;
  mpm_io_input *in;     /* where each value was set */
  mpm_sim_size size;
  double mem_avail;     /* memory available to the run [bytes]; < 0: unknown */
  double disk_free;     /* free space where the output goes [bytes]; < 0: unknown */
  mpm_sim *sim;         /* after mpm_app_plan_build */
} mpm_app_plan;

/* Load the input (file, or text named file when text is not NULL) with the
 * --set overrides, put the output in outdir (NULL: the input's), and check
 * the fills, the time step, the size and that the output can be written. Returns 0, or the exit status
 * after printing the one error line. */
int mpm_app_plan_load(mpm_app_plan *p, const char *file, const char *text,
                      const char *const *sets, int nset, const char *outdir);

/* Build the simulation (p->sim). Returns 0 or the exit status, as above. */
int mpm_app_plan_build(mpm_app_plan *p);

/* The size of the run, as comment lines of an input file. */
void mpm_app_plan_print(const mpm_app_plan *p, FILE *f);

/* Warnings on stderr: a run estimated to take more than a day on one
 * thread, an explicit NGF diffusion that is unstable. */
void mpm_app_plan_warn(const mpm_app_plan *p);

void mpm_app_plan_free(mpm_app_plan *p);  /* the simulation and the input */

#endif
