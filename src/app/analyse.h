/* analyse.h: measurements of a run directory for `granmpm extract`
 * (--profile, --surface, --smooth, --series; docs/diagnostics.md). */
#ifndef MPM_APP_ANALYSE_H
#define MPM_APP_ANALYSE_H
/* 1 if the extract arguments ask for a measurement rather than raw fields. */
int mpm_app_is_analysis(int argc, char **argv);
/* argv[0] = "extract"; returns the process exit status. */
int mpm_app_analyse(int argc, char **argv);
#endif
