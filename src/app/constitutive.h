/* constitutive.h: `granmpm constitutive`, the single-point constitutive driver. */
#ifndef MPM_APP_CONSTITUTIVE_H
#define MPM_APP_CONSTITUTIVE_H
/* argv[0] = "constitutive"; returns the process exit status. */
int mpm_app_constitutive(int argc, char **argv);
#endif
