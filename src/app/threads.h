/* threads.h: the number of OpenMP threads a run uses by default. */
#ifndef MPM_APP_THREADS_H
#define MPM_APP_THREADS_H

/* Unless OMP_NUM_THREADS is set, use as many threads as cores are idle now
 * (measured over 50 ms from /proc/stat; all the cores this process may use
 * when that cannot be read), at least one. Returns the number of threads a
 * parallel region will have (1 without OpenMP). */
int mpm_app_threads_default(void);

#endif
