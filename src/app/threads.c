/* threads.c: the default thread count (threads.h).
 *
 * A step has a few parallel regions, each ending at a barrier. When another
 * job holds one of the cores, the thread that shares that core runs only
 * part of the time, and every barrier waits for it, often a whole time
 * slice: a run on more threads than idle cores is slower than on one thread
 * (README, "Performance"). So the default is the number of cores idle when
 * the run starts; OMP_NUM_THREADS still sets any number. */
#define _POSIX_C_SOURCE 200809L
#include "app/threads.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#ifdef _OPENMP
#include <omp.h>
#endif

/* Busy and total time of all cores and their number, from /proc/stat
 * (user nice system idle iowait irq softirq steal, in clock ticks); 0 on
 * success. */
static int cpu_times(unsigned long long *busy, unsigned long long *total, int *ncpu)
{
  FILE *f = fopen("/proc/stat", "r");
  if (!f)
    return -1;
  char line[512];
  unsigned long long v[8] = {0};
  int ok = 0, n = 0;
  while (fgets(line, sizeof line, f)) {
    if (strncmp(line, "cpu ", 4) == 0)
      ok = sscanf(line + 4, "%llu %llu %llu %llu %llu %llu %llu %llu", &v[0], &v[1], &v[2],
                  &v[3], &v[4], &v[5], &v[6], &v[7]) == 8;
    else if (strncmp(line, "cpu", 3) == 0)
      n++;
  }
  fclose(f);
  if (!ok || n < 1)
    return -1;
  *total = 0;
  for (int k = 0; k < 8; k++)
    *total += v[k];
  *busy = *total - v[3] - v[4];             /* all but idle and iowait */
  *ncpu = n;
  return 0;
}

/* Cores idle over the next 50 ms (rounded down unless within 0.3 of the
 * next whole core), or -1 when that cannot be measured. */
static int idle_cores(void)
{
  unsigned long long b0, t0, b1, t1;
  int n0, n1;
  if (cpu_times(&b0, &t0, &n0) != 0)
    return -1;
  const struct timespec wait = {0, 50000000};
  nanosleep(&wait, NULL);
  if (cpu_times(&b1, &t1, &n1) != 0 || n1 != n0 || t1 <= t0 || b1 < b0)
    return -1;
  const double idle = (double)((t1 - t0) - (b1 - b0)) / (double)(t1 - t0) * n1;
  return (int)(idle + 0.3);
}

int mpm_app_threads_default(void)
{
#ifdef _OPENMP
  if (getenv("OMP_NUM_THREADS"))
    return omp_get_max_threads();
  const int ncpu = omp_get_num_procs();      /* the cores this process may run on */
  int n = ncpu > 1 ? idle_cores() : 1;
  if (n < 0 || n > ncpu)
    n = ncpu;
  if (n < 1)
    n = 1;
  omp_set_num_threads(n);
  return n;
#else
  return 1;
#endif
}
