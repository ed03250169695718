/* info.h: `granmpm info`: a run's provenance and state. */
#ifndef MPM_APP_INFO_H
#define MPM_APP_INFO_H

/* granmpm info RUNDIR [--status]; returns the exit status. */
int mpm_app_info(int argc, char **argv);

#endif
