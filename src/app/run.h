/* run.h: `granmpm check`, `granmpm run` and `granmpm resume` (run.c). */
#ifndef MPM_APP_RUN_H
#define MPM_APP_RUN_H

#include <signal.h>

/* granmpm check FILE [--set ...] [--output DIR]: everything run does before
 * its first step; the resolved input and the run's size on stdout. Returns
 * the exit status. */
int mpm_app_check(int argc, char **argv);

/* granmpm run FILE [--set ...] [--output DIR] [--quiet] [--force] and
 * granmpm resume DIR [--t-end T] [--quiet]; argv[0] is the command,
 * full_argv the whole command line (for run.h5). *stop is the number of a
 * signal that asks the run to stop (0: none), set by the program's signal
 * handler: the run stops after its step with a checkpoint. Returns the exit
 * status (args.h). */
int mpm_app_run(int argc, char **argv, int full_argc, char **full_argv,
                const volatile sig_atomic_t *stop);
int mpm_app_resume(int argc, char **argv, int full_argc, char **full_argv,
                   const volatile sig_atomic_t *stop);

#endif
