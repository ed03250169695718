/* plan.c: load, check and build a run before its first step (plan.h). The
 * size of the run comes from mpm_sim_estimate; this file weighs it against
 * the machine: the memory the run may use (MemAvailable of /proc/meminfo,
 * or free pages, within the cgroup's memory.max and the address-space
 * limit) and the free space of the file system the output goes to. */
#define _POSIX_C_SOURCE 200809L
#include "app/plan.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/statvfs.h>
#include <unistd.h>

#include "app/args.h"
#include "material/material.h"
#include "nonlocal/field.h"

/* ---- the machine ----------------------------------------------------------- */

/* The number after `key` in the text file path (e.g. "MemAvailable:"), < 0
 * if there is none; "max" reads as infinity. */
static double number_in(const char *path, const char *key)
{
  FILE *f = fopen(path, "r");
  char line[256];
  double v = -1.0;
  if (!f)
    return v;
  while (v < 0.0 && fgets(line, sizeof line, f)) {
    const char *p = key[0] ? strstr(line, key) : line;
    if (p == line) {
      p += strlen(key);
      v = strncmp(p + strspn(p, " \t"), "max", 3) == 0 ? INFINITY : strtod(p, NULL);
    }
  }
  fclose(f);
  return v;
}

/* The cgroup (v2) of this process as a directory under /sys/fs/cgroup. */
static int cgroup_dir(char *buf, size_t len)
{
  FILE *f = fopen("/proc/self/cgroup", "r");
  char line[512];
  int ok = 0;
  while (f && !ok && fgets(line, sizeof line, f))
    if (strncmp(line, "0::", 3) == 0) {
      line[strcspn(line, "\n")] = '\0';
      ok = snprintf(buf, len, "/sys/fs/cgroup%s", line + 3) < (int)len;
    }
  if (f)
    fclose(f);
  return ok;
}

static double memory_available(void)
{
  double avail = number_in("/proc/meminfo", "MemAvailable:");
  if (avail >= 0.0) {
    avail *= 1024.0;                                  /* kB */
  } else {
    long pages = sysconf(_SC_AVPHYS_PAGES), size = sysconf(_SC_PAGESIZE);
    avail = pages > 0 && size > 0 ? (double)pages * (double)size : -1.0;
  }
  char dir[400], path[512];
  if (cgroup_dir(dir, sizeof dir)) {
    snprintf(path, sizeof path, "%s/memory.max", dir);
    double max = number_in(path, "");
    snprintf(path, sizeof path, "%s/memory.current", dir);
    double cur = number_in(path, "");
    if (max >= 0.0 && isfinite(max) && cur >= 0.0 && (avail < 0.0 || max - cur < avail))
      avail = max - cur;
  }
  struct rlimit rl;
  if (getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY &&
      (avail < 0.0 || (double)rl.rlim_cur < avail))
    avail = (double)rl.rlim_cur;
  return avail;
}

/* Free space for an unprivileged writer on the file system of dir, or of
 * its nearest existing parent (the run creates dir). */
static double disk_free(const char *dir)
{
  char path[MPM_PATH_MAX];
  struct statvfs sv;
  snprintf(path, sizeof path, "%s", dir);
  for (;;) {
    if (statvfs(path[0] ? path : ".", &sv) == 0)
      return (double)sv.f_bavail * (double)sv.f_frsize;
    char *slash = strrchr(path, '/');
    if (!path[0] || !slash)
      return statvfs(".", &sv) == 0 ? (double)sv.f_bavail * (double)sv.f_frsize : -1.0;
    *slash = '\0';
    if (slash == path)
      snprintf(path, sizeof path, "/");
  }
}

/* ---- the checks ------------------------------------------------------------- */

static int fail(mpm_app_plan *p, const char *key, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

/* The error at key, printed; returns the usage exit status. */
static int fail(mpm_app_plan *p, const char *key, const char *fmt, ...)
{
  char body[MPM_ERR_MSG];
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(body, sizeof body, fmt, ap);
  va_end(ap);
  mpm_err err = {0};
  mpm_io_input_fail(p->in, &p->cfg, key, &err, "%s", body);
  fprintf(stderr, "granmpm: %s\n", err.msg);
  return MPM_APP_EXIT_USAGE;
}

static const char *fill_key(const mpm_config *cfg, int f, char *buf, size_t len)
{
  snprintf(buf, len, "fill.%s.ppu", cfg->fill[f].name);
  return buf;
}

/* Every fill makes at least one point (as the fill itself will find). */
static int check_fills(mpm_app_plan *p)
{
  for (int f = 0; f < p->cfg.nfill; f++) {
    const mpm_fill_config *fc = &p->cfg.fill[f];
    char key[3 * MPM_NAME_MAX];
    if (p->size.fill_points[f] == 0)
      return fail(p, fill_key(&p->cfg, f, key, sizeof key),
                  "the region holds no point: no centre of the %d x %d sub-cells of a unit "
                  "(%.3g m x %.3g m each) lies in it (allowed: a region or a ppu that puts at "
                  "least one point in the fill)", fc->ppu, fc->ppu, p->cfg.mesh.dx / fc->ppu,
                  p->cfg.mesh.dy / fc->ppu);
  }
  return 0;
}

/* The time step within the stable one, and a number of substeps that fits. */
static int check_time(mpm_app_plan *p)
{
  const mpm_sim_size *z = &p->size;
  const mpm_config *c = &p->cfg;
  if (c->time.dt > 0.0 && z->dt > z->dt_stable * (1.0 + 1e-12) && !c->time.dt_unstable_ok)
    return fail(p, "time.dt", "dt = %g s is %.3g times the stable step %.6g s (min(dx, dy) / "
                "(P-wave speed + fill speed), cfl = 1; allowed: at most %.6g s, or "
                "time.dt_unstable_ok = true)", z->dt, z->dt / z->dt_stable, z->dt_stable,
                z->dt_stable);
  if (z->n_sub > 1e6)
    return fail(p, "material.dt_sub", "dt_sub = %g s makes %.3g substeps in each step of %g s "
                "(allowed: at most 1e6 substeps, dt_sub >= %.6g s)", c->material.dt_sub,
                z->n_sub, z->dt, z->dt / 1e6);
  return 0;
}

/* The biggest fill, for a key to name with the memory estimate. */
static int biggest_fill(const mpm_app_plan *p)
{
  int big = 0;
  for (int f = 1; f < p->cfg.nfill; f++)
    if (p->size.fill_points[f] > p->size.fill_points[big])
      big = f;
  return big;
}

static int check_size(mpm_app_plan *p)
{
  const mpm_sim_size *z = &p->size;
  char key[3 * MPM_NAME_MAX];
  if (p->cfg.output.allow_large)
    return 0;
  if (p->mem_avail >= 0.0 && z->memory > p->mem_avail)
    return fail(p, fill_key(&p->cfg, biggest_fill(p), key, sizeof key),
                "the run needs about %.3g bytes of memory (%zu points, %ld nodes), more than the "
                "%.3g bytes available (allowed: at most the available memory, or "
                "output.allow_large = true)", z->memory, z->points, z->nodes, p->mem_avail);
  if (p->disk_free >= 0.0 && z->output > p->disk_free)
    return fail(p, "time.frame_dt",
                "the run writes about %.3g bytes (%.3g frames of %zu points), more than the "
                "%.3g bytes free on the file system of '%s' (allowed: at most the free space, "
                "or output.allow_large = true)", z->output, z->frames, z->points, p->disk_free,
                p->cfg.output.dir);
  return 0;
}

/* Whether the run can write in dir as it will (io/output.c: the directory
 * and its missing parents created, then files created in it), tried without
 * leaving anything: a file made and removed in dir, or, when dir does not
 * exist yet, a directory made and removed in its nearest existing parent.
 * 0, or -1 with why in buf. */
static int try_output(const char *dir, char *buf, size_t len)
{
  struct stat st;
  char path[MPM_PATH_MAX + 32];
  if (stat(dir, &st) == 0) {
    if (!S_ISDIR(st.st_mode)) {
      snprintf(buf, len, "it is not a directory");
      return -1;
    }
    snprintf(path, sizeof path, "%s/.granmpm-check-XXXXXX", dir);
    const int fd = mkstemp(path);
    if (fd < 0) {
      snprintf(buf, len, "cannot create a file in it: %s", strerror(errno));
      return -1;
    }
    close(fd);
    unlink(path);
    return 0;
  }
  if (errno != ENOENT) {
    snprintf(buf, len, "%s", strerror(errno));
    return -1;
  }
  char parent[MPM_PATH_MAX];              /* the nearest existing parent */
  snprintf(parent, sizeof parent, "%s", dir);
  for (;;) {
    char *slash = strrchr(parent, '/');
    while (slash && slash > parent && slash[-1] == '/')
      slash--;
    if (!slash)
      snprintf(parent, sizeof parent, ".");
    else if (slash == parent)
      snprintf(parent, sizeof parent, "/");
    else
      *slash = '\0';
    if (stat(parent, &st) == 0 || errno != ENOENT || !slash || strcmp(parent, "/") == 0)
      break;
  }
  if (stat(parent, &st) != 0 || !S_ISDIR(st.st_mode)) {
    snprintf(buf, len, "its parent '%s' is %s", parent,
             stat(parent, &st) != 0 ? strerror(errno) : "not a directory");
    return -1;
  }
  snprintf(path, sizeof path, "%s/.granmpm-check-XXXXXX", parent);
  if (!mkdtemp(path)) {
    snprintf(buf, len, "cannot create a directory in '%s': %s", parent, strerror(errno));
    return -1;
  }
  rmdir(path);
  return 0;
}

/* The output directory can be written as the run will write it: from the
 * input (output.dir, named by its line) or from the command line. */
static int check_output(mpm_app_plan *p, int given)
{
  char why[MPM_PATH_MAX + 160];
  const char *dir = p->cfg.output.dir;
  if (try_output(dir, why, sizeof why) == 0)
    return 0;
  if (!given)
    return fail(p, "output.dir", "the run cannot write its output in '%s': %s (allowed: a "
                "directory that can be created, or one this user may write in)", dir, why);
  fprintf(stderr, "granmpm: output directory '%s': the run cannot write its output there: %s "
          "(allowed: a directory that can be created, or one this user may write in)\n", dir,
          why);
  return MPM_APP_EXIT_USAGE;
}

int mpm_app_plan_load(mpm_app_plan *p, const char *file, const char *text,
                      const char *const *sets, int nset, const char *outdir)
{
  memset(p, 0, sizeof *p);
  p->file = file;
  mpm_err err = {0};
  int rc = text ? mpm_io_input_open_text(&p->in, file, text, sets, nset, &p->cfg, &err)
                : mpm_io_input_open(&p->in, file, sets, nset, &p->cfg, &err);
  if (rc != MPM_OK) {
    fprintf(stderr, "granmpm: %s\n", err.msg);
    return rc == MPM_ENOMEM ? MPM_APP_EXIT_RUNTIME : MPM_APP_EXIT_USAGE;
  }
  if (outdir) {
    if (strlen(outdir) >= sizeof p->cfg.output.dir)
      return mpm_app_usage("--output '%s': path too long", outdir);
    strcpy(p->cfg.output.dir, outdir);
  }
  mpm_sim_estimate(&p->cfg, &p->size);
  p->mem_avail = memory_available();
  p->disk_free = disk_free(p->cfg.output.dir);
  int st = check_fills(p);
  if (st == 0)
    st = check_time(p);
  if (st == 0)
    st = check_size(p);
  if (st == 0)
    st = check_output(p, outdir != NULL);
  return st;
}

int mpm_app_plan_build(mpm_app_plan *p)
{
  mpm_err err = {0};
  if (mpm_sim_create(&p->sim, &p->cfg, &err) == MPM_OK) {
    if (p->sim->pts->n != p->size.points)   /* bodies carved the fills */
      mpm_sim_estimate_points(&p->cfg, p->sim->pts->n, &p->size);
    return 0;
  }
  /* an input the simulation refuses at a key ("key 'K': ..."): where K was set */
  char key[4 * MPM_NAME_MAX];
  int off = 0;
  if (err.code == MPM_EINPUT && p->in &&
      sscanf(err.msg, "key '%95[^']': %n", key, &off) == 1 && off > 0)
    return fail(p, key, "%s", err.msg + off);
  fprintf(stderr, "granmpm: %s: %s\n", p->file, err.msg);
  return err.code == MPM_ENOMEM ? MPM_APP_EXIT_RUNTIME : MPM_APP_EXIT_USAGE;
}

/* bytes as "12.3 MB" */
static void human(double b, char *buf, size_t len)
{
  const char *unit[] = {"bytes", "kB", "MB", "GB", "TB", "PB", "EB"};
  int k = 0;
  while (b >= 1000.0 && k < 6) {
    b /= 1000.0;
    k++;
  }
  snprintf(buf, len, k ? "%.3g %s" : "%.0f %s", b, unit[k]);
}

/* seconds as "45 s", "3.2 min", "5.1 h", "137 days" or "12 years" */
static void duration(double s, char *buf, size_t len)
{
  if (s < 60.0)
    snprintf(buf, len, "%.2g s", s);
  else if (s < 3600.0)
    snprintf(buf, len, "%.2g min", s / 60.0);
  else if (s < 86400.0)
    snprintf(buf, len, "%.2g h", s / 3600.0);
  else if (s < 365.0 * 86400.0)
    snprintf(buf, len, "%.3g days", s / 86400.0);
  else
    snprintf(buf, len, "%.3g years", s / (365.0 * 86400.0));
}

/* Above this estimated run time on one thread a run gets a warning. */
#define LONG_RUN_SECONDS 86400.0

void mpm_app_plan_print(const mpm_app_plan *p, FILE *f)
{
  const mpm_sim_size *z = &p->size;
  char mem[32], avail[32], out[32], free_[32];
  human(z->memory, mem, sizeof mem);
  human(p->mem_avail, avail, sizeof avail);
  human(z->output, out, sizeof out);
  human(p->disk_free, free_, sizeof free_);
  fprintf(f, "# size: %zu points, %ld nodes, %.6g steps of %.6g s (stable: %.6g s), "
          "%.6g substeps per step, at most %.6g frames\n", z->points, z->nodes, z->steps, z->dt,
          z->dt_stable, z->n_sub, z->frames);
  fprintf(f, "# estimated memory %s (%s available), output %s (%s free where it goes)\n", mem,
          p->mem_avail >= 0.0 ? avail : "unknown", out, p->disk_free >= 0.0 ? free_ : "unknown");
  char when[32];
  duration(z->seconds, when, sizeof when);
  fprintf(f, "# estimated run time %s on one thread (%.6g steps x %.6g substeps x %zu points; "
          "docs/input-reference.md, \"The size of a run\")\n", when, z->steps, z->n_sub,
          z->points);
}

/* A run estimated to take more than a day on one thread: a warning naming
 * the key that makes it long (the substeps when they take most of it). */
static void warn_long(const mpm_app_plan *p)
{
  const mpm_sim_size *z = &p->size;
  if (!(z->seconds > LONG_RUN_SECONDS))
    return;
  char when[32];
  duration(z->seconds, when, sizeof when);
  const char *key = 2.0 * z->sub_seconds < z->seconds ? "time.t_end"
                    : p->cfg.material.dt_sub > 0.0    ? "material.dt_sub"
                                                      : "material.n_sub";
  fprintf(stderr, "granmpm: warning: %s: the run would take about %s on one thread (%.6g "
          "steps x %.6g substeps x %zu points; more than a day) (key '%s')\n", p->file, when,
          z->steps, z->n_sub, z->points, key);
}

/* Warnings on stderr, not errors: a run estimated to take more than a day
 * on one thread; a nonlocal model whose explicit diffusion of g is unstable
 * at the planned time step and substeps (MODEL.md section 5; the implicit
 * diffusion has no such limit). */
void mpm_app_plan_warn(const mpm_app_plan *p)
{
  warn_long(p);
  const mpm_config *cfg = &p->cfg;
  const mpm_material_type *t = mpm_material_lookup(cfg->material.model);
  const mpm_nonlocal_diffusion *d = mpm_nonlocal_diffusion_name(cfg->material.diffusion)
                                        ? mpm_nonlocal_diffusion_table[cfg->material.diffusion]
                                        : NULL;
  if (!t || !t->nonlocal || !d || !d->stability_limited)
    return;
  double dt;
  int n_sub;
  mpm_sim_time_plan(cfg, &dt, &n_sub);
  mpm_material_params par;
  mpm_material_params_from_config(&par, cfg);
  mpm_err err = {0};
  if (mpm_material_ngf_check_diffusion(&par, dt, n_sub, cfg->mesh.dx, cfg->mesh.dy,
                                       cfg->mesh.nz > 0 ? cfg->mesh.dz : 0.0, &err) != MPM_OK)
    fprintf(stderr, "granmpm: warning: %s: %s (key 'material.n_sub')\n", p->file, err.msg);
}

void mpm_app_plan_free(mpm_app_plan *p)
{
  mpm_sim_free(p->sim);
  mpm_io_input_free(p->in);
  p->sim = NULL;
  p->in = NULL;
}
