/* run.c: `granmpm run` and `granmpm resume`: a run from its input, or from
 * the checkpoint of a run that stopped, to its end, with frames, diagnostics,
 * checkpoints, progress, and a stop on request that leaves a checkpoint.
 *
 * A run ends in one of four ways, each with its exit status and its status
 * in run.h5: finished (0, "finished": t_end or a stop test; the checkpoint
 * is removed), stopped on request by a signal (3, "stopped": a checkpoint
 * and a last frame written, one line saying how to resume), failed (1,
 * "failed": a physical or I/O failure, one line saying what), or refused
 * before its first step (2: bad input, an occupied output directory, a size
 * the machine cannot hold). */
#define _POSIX_C_SOURCE 200809L
#include "app/run.h"

#include "config.h"
#include "revision.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "app/args.h"
#include "app/plan.h"
#include "app/threads.h"
#include "diag/region.h"

enum { MAX_SET = 256 };

/* ---- the run's callbacks ------------------------------------------------------ */

typedef struct run_ctx {
  mpm_io_output *out;
  const char *dir;
  const char *input;                  /* resolved input text, for checkpoints */
  const volatile sig_atomic_t *stop;  /* the signal that asks the run to stop, 0: none */
  int quiet, tty;
  double *ft, *fm;                    /* time and region mass of every frame (flow rate) */
  size_t nf, capf;
} run_ctx;

/* Keep (t, mass in region) of a frame; 0 when out of memory. */
static int keep_frame(run_ctx *c, double t, double m)
{
  if (c->nf == c->capf) {
    size_t cap = c->capf ? 2 * c->capf : 256;
    double *a = realloc(c->ft, cap * sizeof *a);
    if (!a)
      return 0;
    c->ft = a;
    double *b = realloc(c->fm, cap * sizeof *b);
    if (!b)
      return 0;
    c->fm = b;
    c->capf = cap;
  }
  c->ft[c->nf] = t;
  c->fm[c->nf++] = m;
  return 1;
}

static int on_frame(void *vctx, const mpm_sim *s, mpm_err *err)
{
  run_ctx *c = vctx;
  mpm_diag d;
  mpm_diag_compute(s->pts, s->t, &d);
  d.stop = s->stop;
  d.mass_removed = s->mass_removed;
  d.nremoved = s->nremoved;
  d.mass_region = mpm_sim_region_mass(s);
  if (!keep_frame(c, d.t, d.mass_region))
    return mpm_err_set(err, MPM_ENOMEM, "frame %ld: out of memory", s->frames);
  if (s->nbody > 0) {
    mpm_body_state b[MPM_MAX_BODIES];
    const char *names[MPM_MAX_BODIES];
    mpm_io_outline ol[MPM_MAX_BODIES];
    double xyz_all[MPM_MAX_BODIES][2 * 3 * MPM_BODY_OUTLINE_MAX];  /* 24 kB */
    mpm_sim_bodies_state(s, b);
    for (int k = 0; k < s->nbody; k++) {
      names[k] = s->cfg.body[k].name;
      double *xyz = xyz_all[k];
      ol[k].xyz = xyz;
      ol[k].nv = mpm_body_outline(&s->body[k], &s->mesh, xyz, &ol[k].nr, &ol[k].caps);
    }
    const int rc = mpm_io_output_bodies(c->out, s->t, s->nbody, names, b, ol, err);
    if (rc != MPM_OK)
      return rc;
  }
  return mpm_io_output_frame(c->out, s->pts, &d, err);
}

/* "VERSION (REVISION)" of this program. */
static void this_program(char *buf, size_t len)
{
  snprintf(buf, len, "%s (%s)", PACKAGE_VERSION, GRANMPM_REVISION);
}

static int on_checkpoint(void *vctx, const mpm_sim *s, mpm_err *err)
{
  run_ctx *c = vctx;
  mpm_run_state st = {0};
  char by[128];
  mpm_sim_state_get(s, &st);
  st.nseries = c->nf;
  st.series_t = c->ft;
  st.series_m = c->fm;
  this_program(by, sizeof by);
  return mpm_io_checkpoint_write(c->dir, &st, c->input, by, err);
}

static int on_stop_request(void *vctx)
{
  const run_ctx *c = vctx;
  return c->stop && *c->stop != 0;
}

static void on_progress(void *vctx, const mpm_sim *s, double steps_per_s)
{
  const run_ctx *c = vctx;
  if (c->quiet || !c->tty)
    return;
  double left = (s->cfg.time.t_end - s->t) / s->dt / (steps_per_s > 0 ? steps_per_s : 1);
  fprintf(stderr, "\rt = %.4g / %.4g s  %.0f steps/s  %ld points  ETA %02d:%02d:%02d ",
          s->t, s->cfg.time.t_end, steps_per_s, (long)s->pts->n,
          (int)(left / 3600), (int)(left / 60) % 60, (int)left % 60);
}

/* ---- pieces ----------------------------------------------------------------------- */

/* The command line as one string, for the output attributes. */
static char *join_args(int argc, char **argv)
{
  size_t len = 1;
  for (int i = 0; i < argc; i++)
    len += strlen(argv[i]) + 3;
  char *s = malloc(len), *q = s;
  if (!s)
    return NULL;
  for (int i = 0; i < argc; i++)
    q += sprintf(q, i ? " %s" : "%s", argv[i]);
  return s;
}

static int threads(void)
{
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}

/* Flow rate fitted to the region mass of the frames between region.m_lo and
 * region.m_hi: on stderr and in DIR/flow-rate.txt ("Q n_frames m_hi m_lo").
 * Too few frames in the band is said, not an error. */
static int report_flow_rate(const run_ctx *c, const mpm_config *cfg, mpm_err *err)
{
  double q = 0.0;
  size_t n = 0;
  mpm_err ferr = {0};
  if (mpm_diag_region_flow_rate(c->ft, c->fm, c->nf, cfg->region.m_hi, cfg->region.m_lo, &q,
                                &n, &ferr) != MPM_OK) {
    fprintf(stderr, "granmpm: no flow rate: %s\n", ferr.msg);
    return MPM_OK;
  }
  const int d3 = cfg->mesh.nz > 0;           /* masses per unit thickness in the plane */
  fprintf(stderr, "granmpm: flow rate Q = %.6g %s from %zu frames with %g <= mass <= %g %s\n", q,
          d3 ? "kg/s" : "kg/(m s)", n, cfg->region.m_lo, cfg->region.m_hi, d3 ? "kg" : "kg/m");
  char path[MPM_PATH_MAX + 32];
  snprintf(path, sizeof path, "%s/flow-rate.txt", cfg->output.dir);
  FILE *f = fopen(path, "w");
  if (!f)
    return mpm_err_set(err, MPM_EIO, "cannot write '%s': %s", path, strerror(errno));
  int bad = fprintf(f, "%.10g %zu %.10g %.10g\n", q, n, cfg->region.m_hi, cfg->region.m_lo) < 0;
  bad |= fclose(f) != 0;
  return bad ? mpm_err_set(err, MPM_EIO, "cannot write '%s'", path) : MPM_OK;
}

static const char *signal_name(int sig)
{
  switch (sig) {
  case SIGINT: return "SIGINT";
  case SIGTERM: return "SIGTERM";
  case SIGHUP: return "SIGHUP";
  case SIGUSR1: return "SIGUSR1";
  default: return "a signal";
  }
}

/* Step the built simulation to its end with the output open; report; close.
 * Returns the exit status. */
static int execute(mpm_app_plan *p, run_ctx *ctx)
{
  mpm_sim *sim = p->sim;
  const mpm_config *cfg = &p->cfg;
  mpm_err err = {0};
  const mpm_sim_hooks hooks = {.ctx = ctx, .frame = on_frame, .progress = on_progress,
                               .checkpoint = on_checkpoint, .stop_requested = on_stop_request};
  int st = mpm_sim_run(sim, &hooks, &err);
  if (ctx->tty && !ctx->quiet)
    fputc('\n', stderr);
  const int stopped = st == MPM_OK && sim->stop == MPM_STOP_REQUEST;
  mpm_err cerr = {0};
  if (mpm_io_output_end(ctx->out, st != MPM_OK ? "failed" : stopped ? "stopped" : "finished",
                        st != MPM_OK ? err.msg : "", &cerr) != MPM_OK && st == MPM_OK) {
    st = cerr.code;
    err = cerr;
  }
  if (mpm_io_output_close(ctx->out, &cerr) != MPM_OK && st == MPM_OK) {
    st = cerr.code;
    err = cerr;
  }
  ctx->out = NULL;
  if (st == MPM_OK && !stopped && mpm_io_checkpoint_remove(cfg->output.dir, &cerr) != MPM_OK) {
    st = cerr.code;                   /* a finished run needs no checkpoint */
    err = cerr;
  }
  if (st != MPM_OK) {
    fprintf(stderr, "granmpm: %s\n", err.msg);
    return MPM_APP_EXIT_RUNTIME;
  }
  if (stopped) {                      /* said even with --quiet */
    fprintf(stderr, "granmpm: stopped by %s at t = %.6g s (step %ld), checkpoint written; "
            "continue with: granmpm resume %s\n", signal_name(*ctx->stop), sim->t, sim->step,
            cfg->output.dir);
    return MPM_APP_EXIT_STOPPED;
  }
  if (sim->stop == MPM_STOP_KE)
    fprintf(stderr, "granmpm: stopped at t = %.6g s (before t_end = %.6g s): kinetic energy "
            "per unit mass %.3g J/kg < stop.ke = %.3g J/kg\n", sim->t, cfg->time.t_end,
            sim->stop_value, cfg->stop.ke);
  else if (sim->stop == MPM_STOP_MASS)
    fprintf(stderr, "granmpm: stopped at t = %.6g s (before t_end = %.6g s): mass in region "
            "%.6g %s < stop.mass = %.6g %s\n", sim->t, cfg->time.t_end, sim->stop_value,
            cfg->mesh.nz > 0 ? "kg" : "kg/m", cfg->stop.mass, cfg->mesh.nz > 0 ? "kg" : "kg/m");
  if (cfg->region.m_hi > 0.0 && report_flow_rate(ctx, cfg, &err) != MPM_OK) {
    fprintf(stderr, "granmpm: %s\n", err.msg);
    return MPM_APP_EXIT_RUNTIME;
  }
  if (!ctx->quiet)
    fprintf(stderr, "granmpm: %ld steps of %.4g s (%d substep%s), %ld frames, %zu points, "
            "%d thread%s -> %s/run.h5\n", sim->step, sim->dt, sim->n_sub,
            sim->n_sub == 1 ? "" : "s", sim->frames, sim->pts->n, threads(),
            threads() == 1 ? "" : "s", cfg->output.dir);
  return 0;
}

/* The built run of plan p with its output opened (new, or reopened after
 * `reopen` frames when reopen >= 0), stepped to its end; then everything of
 * ctx freed. Returns the exit status (st when it is not 0 already). */
static int open_and_execute(int st, mpm_app_plan *p, run_ctx *ctx, int argc, char **argv,
                            long reopen)
{
  char *cmdline = st == 0 ? join_args(argc, argv) : NULL;
  char *text = st == 0 ? mpm_io_input_text(&p->cfg) : NULL;  /* resolved, for run.h5 and checkpoints */
  mpm_err err = {0};
  if (st == 0 && (!cmdline || !text)) {
    fprintf(stderr, "granmpm: out of memory\n");
    st = MPM_APP_EXIT_RUNTIME;
  }
  if (st == 0) {
    const mpm_io_origin origin = {cmdline, GRANMPM_REVISION, threads()};
    ctx->input = text;
    const mpm_sim *sim = p->sim;
    int rc = reopen >= 0 ? mpm_io_output_reopen(&ctx->out, ctx->dir, &origin, reopen, &err)
                         : mpm_io_output_open(&ctx->out, ctx->dir, &origin, text, &sim->mesh, &err);
    if (rc != MPM_OK) {
      fprintf(stderr, "granmpm: %s\n", err.msg);
      st = MPM_APP_EXIT_RUNTIME;
    } else {
      st = execute(p, ctx);
    }
  }
  free(cmdline);
  free(text);
  free(ctx->ft);
  free(ctx->fm);
  mpm_app_plan_free(p);
  return st;
}

/* ---- run ------------------------------------------------------------------------- */

typedef struct run_opts {
  const char *file;
  const char *sets[MAX_SET];
  int nset;
  const char *outdir;
  int quiet, force;
} run_opts;

static int parse_run(int argc, char **argv, run_opts *o)
{
  memset(o, 0, sizeof *o);
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    if (strcmp(a, "--set") == 0 || strncmp(a, "--set=", 6) == 0) {
      const char *v = a[5] == '=' ? a + 6 : (i + 1 < argc ? argv[++i] : NULL);
      if (!v)
        return mpm_app_usage("%s needs section.key=value", "--set");
      if (o->nset == MAX_SET)
        return mpm_app_usage("too many %s options", "--set");
      o->sets[o->nset++] = v;
    } else if (strcmp(a, "--output") == 0) {
      if (i + 1 >= argc)
        return mpm_app_usage("%s needs a directory", "--output");
      o->outdir = argv[++i];
    } else if (strcmp(a, "--quiet") == 0) {
      o->quiet = 1;
    } else if (strcmp(a, "--force") == 0 && strcmp(argv[0], "run") == 0) {
      o->force = 1;
    } else {
      int st = mpm_app_arg_positional(argv[0], a, &o->file, 1);
      if (st != 0)
        return st;
    }
  }
  if (!o->file)
    return mpm_app_usage("%s: an input FILE is required", argv[0]);
  return 0;
}

/* The options and the input of check and run (p is freed by the caller
 * whatever this returns). */
static int load_run(int argc, char **argv, run_opts *o, mpm_app_plan *p)
{
  memset(p, 0, sizeof *p);
  int st = parse_run(argc, argv, o);
  return st != 0 ? st : mpm_app_plan_load(p, o->file, NULL, o->sets, o->nset, o->outdir);
}

int mpm_app_check(int argc, char **argv)
{
  run_opts o;
  mpm_app_plan p;
  int st = load_run(argc, argv, &o, &p);
  if (st == 0)
    st = mpm_app_plan_build(&p);
  if (st == 0) {
    mpm_io_input_write(stdout, &p.cfg);
    mpm_app_plan_print(&p, stdout);
    mpm_app_plan_warn(&p);
  }
  mpm_app_plan_free(&p);
  if (st == 0 && fflush(stdout) != 0)
    st = MPM_APP_EXIT_RUNTIME;
  return st;
}

/* The output directory taken for this process's writing (mpm_io_dir_lock):
 * 0, or the exit status with the holder named. */
static int take_dir(const char *dir, int *lock)
{
  mpm_err err = {0};
  const int rc = mpm_io_dir_lock(dir, lock, &err);
  if (rc == MPM_OK)
    return 0;
  fprintf(stderr, "granmpm: %s\n", err.msg);
  return rc == MPM_EINPUT ? MPM_APP_EXIT_USAGE : MPM_APP_EXIT_RUNTIME;
}

/* A directory that holds a run is replaced only when asked (--force). */
static int claim_output(const char *dir, int force)
{
  const char *what = NULL;
  if (!mpm_io_output_occupied(dir, &what))
    return 0;
  if (!force) {
    fprintf(stderr, "granmpm: output directory '%s' holds a run (%s): replace it with --force, "
            "or continue it with: granmpm resume %s\n", dir, what, dir);
    return MPM_APP_EXIT_USAGE;
  }
  mpm_err err = {0};
  char path[MPM_PATH_MAX + 32];
  snprintf(path, sizeof path, "%s/flow-rate.txt", dir);
  if (mpm_io_checkpoint_remove(dir, &err) != MPM_OK || (unlink(path) != 0 && errno != ENOENT)) {
    fprintf(stderr, "granmpm: %s\n", err.msg[0] ? err.msg : strerror(errno));
    return MPM_APP_EXIT_RUNTIME;
  }
  return 0;
}

int mpm_app_run(int argc, char **argv, int full_argc, char **full_argv,
                const volatile sig_atomic_t *stop)
{
  run_opts o;
  mpm_app_plan p;
  int st = load_run(argc, argv, &o, &p), lock = -1;
  if (st == 0)
    st = take_dir(p.cfg.output.dir, &lock);
  if (st == 0)
    st = claim_output(p.cfg.output.dir, o.force);
  if (st == 0) {
    mpm_app_plan_warn(&p);
    mpm_app_threads_default();
    st = mpm_app_plan_build(&p);
  }
  run_ctx ctx = {.dir = p.cfg.output.dir, .stop = stop, .quiet = o.quiet,
                 .tty = isatty(STDERR_FILENO)};
  st = open_and_execute(st, &p, &ctx, full_argc, full_argv, -1);
  mpm_io_dir_unlock(lock);
  return st;
}

/* ---- resume ---------------------------------------------------------------------- */

/* The checkpoint's state into the simulation just built from its input,
 * and the frame series into the context. Returns 0 or the exit status. */
static int restore(mpm_app_plan *p, mpm_io_checkpoint *ck, run_ctx *ctx)
{
  mpm_err err = {0};
  if (mpm_sim_state_set(p->sim, &ck->state, &err) != MPM_OK) {
    fprintf(stderr, "granmpm: %s: %s\n", p->file, err.msg);
    return MPM_APP_EXIT_USAGE;
  }
  ctx->ft = ck->state.series_t;     /* the series now belong to the run */
  ctx->fm = ck->state.series_m;
  ctx->nf = ctx->capf = ck->state.nseries;
  ck->state.series_t = ck->state.series_m = NULL;
  return 0;
}

int mpm_app_resume(int argc, char **argv, int full_argc, char **full_argv,
                   const volatile sig_atomic_t *stop)
{
  const char *dir = NULL, *tend = NULL;
  int quiet = 0;
  for (int i = 1; i < argc; i++) {
    int st = 0;
    if (strcmp(argv[i], "--t-end") == 0 && i + 1 < argc)
      tend = argv[++i];
    else if (strcmp(argv[i], "--quiet") == 0)
      quiet = 1;
    else
      st = mpm_app_arg_positional("resume", argv[i], &dir, 1);
    if (st != 0)
      return st;
  }
  if (!dir)
    return mpm_app_usage("%s: a run directory is required", "resume");
  double t_end = 0.0;
  if (tend && !mpm_app_arg_real(tend, &t_end))
    return mpm_app_usage("resume: --t-end expects a time in seconds, got '%s'", tend);
  mpm_io_checkpoint ck;
  mpm_err err = {0};
  struct stat sb;
  int lock = -1;
  if (stat(dir, &sb) != 0 || !S_ISDIR(sb.st_mode)) {
    fprintf(stderr, "granmpm: nothing to resume in '%s': not a directory\n", dir);
    return MPM_APP_EXIT_USAGE;
  }
  int st = take_dir(dir, &lock);
  if (st != 0)
    return st;
  if (mpm_io_checkpoint_read(dir, &ck, &err) != MPM_OK) {
    fprintf(stderr, "granmpm: nothing to resume in '%s': %s\n", dir, err.msg);
    mpm_io_dir_unlock(lock);
    return MPM_APP_EXIT_USAGE;
  }
  if (tend && !(t_end > ck.state.t)) {
    const double t = ck.state.t;
    mpm_io_checkpoint_clear(&ck);
    mpm_io_dir_unlock(lock);
    return mpm_app_usage("resume: --t-end %s is not after the checkpoint's t = %.17g s", tend, t);
  }
  char by[128], name[MPM_PATH_MAX + 32], set[64];
  this_program(by, sizeof by);
  if (strcmp(by, ck.written_by) != 0)
    fprintf(stderr, "granmpm: warning: the checkpoint was written by granmpm %s, this is %s: "
            "the continued run may differ from an uninterrupted one\n", ck.written_by, by);
  snprintf(name, sizeof name, "%s/checkpoint.h5", dir);
  snprintf(set, sizeof set, "time.t_end=%s", tend ? tend : "");
  const char *sets[] = {set};
  mpm_app_plan p;
  run_ctx ctx = {.dir = dir, .stop = stop, .quiet = quiet, .tty = isatty(STDERR_FILENO)};
  st = mpm_app_plan_load(&p, name, ck.input, sets, tend ? 1 : 0, dir);
  if (st == 0) {
    mpm_app_threads_default();
    st = mpm_app_plan_build(&p);
  }
  if (st == 0)
    st = restore(&p, &ck, &ctx);
  st = open_and_execute(st, &p, &ctx, full_argc, full_argv, ck.state.frames);
  mpm_io_checkpoint_clear(&ck);
  mpm_io_dir_unlock(lock);
  return st;
}
