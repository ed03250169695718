/* main.c: the `granmpm` command line: run, check, extract, constitutive.
 *
 * The only place that prints to the user or exits. Exit status: 0 success,
 * 1 a run failed (physical or I/O failure while running), 2 bad usage or
 * input (one error line naming file, line, key and what is allowed). */
#define _POSIX_C_SOURCE 200809L
#include "config.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/analyse.h"
#include "app/args.h"
#include "app/constitutive.h"
#include "app/state.h"
#include "diag/diag.h"
#include "diag/region.h"
#include "io/io.h"
#include "solver/solver.h"

enum { MAX_SET = 256 };

static const char usage_text[] =
  "usage: granmpm COMMAND [ARGS]\n"
  "\n"
  "commands:\n"
  "  run FILE [--set section.key=value]... [--output DIR] [--quiet]\n"
  "        run the case described by FILE; writes DIR/run.h5, run.xdmf, diagnostics.csv\n"
  "  check FILE [--set section.key=value]...\n"
  "        validate FILE and print the fully resolved input\n"
  "  extract RUNDIR [--frame N|last] [--fields a,b,c]\n"
  "        print one output frame as CSV with a header row\n"
  "  extract RUNDIR --profile N [--frame N|last] [--range YMIN:YMAX]\n"
  "  extract RUNDIR --surface [--frame N|last] [--width W]\n"
  "  extract RUNDIR --smooth [--frame N|last]\n"
  "  extract RUNDIR --series [--gdot-min G] [--front-cell H] [--front-min K]\n"
  "                 [--slope XA:XB|auto] [--width W]\n"
  "        measurements: velocity profile, free surface, smoothed pressure,\n"
  "        per-frame speed, acceleration, mu, front, slope (docs/diagnostics.md)\n"
  "  extract RUNDIR --jam\n"
  "        silo classifier of [DK-silo] 7.2: static, flowing or unsure, with evidence\n"
  "  extract RUNDIR --roughness [--frame N|last] [--radius R]\n"
  "        pressure roughness and dense fraction of a frame (docs/diagnostics.md)\n"
  "  state INPUT RUNDIR [--frame N|last]\n"
  "        nodal density projected back to the points of one frame, and the\n"
  "        state it gives (dense / disconnected), as CSV\n"
  "  constitutive [ARGS]\n"
  "        drive one material point through a velocity-gradient history\n"
  "        (granmpm constitutive --help)\n"
  "  --version, --help\n";

/* Options shared by run and check. */
typedef struct run_opts {
  const char *file;
  const char *sets[MAX_SET];
  int nset;
  const char *outdir;
  int quiet;
} run_opts;

static int parse_run_opts(int argc, char **argv, int allow_run_opts, run_opts *o)
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
    } else if (allow_run_opts && strcmp(a, "--output") == 0) {
      if (i + 1 >= argc)
        return mpm_app_usage("%s needs a directory", "--output");
      o->outdir = argv[++i];
    } else if (allow_run_opts && strcmp(a, "--quiet") == 0) {
      o->quiet = 1;
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

static int load_input(const run_opts *o, mpm_config *cfg)
{
  mpm_err err = {0};
  if (mpm_io_input_load(o->file, o->sets, o->nset, cfg, &err) != MPM_OK) {
    fprintf(stderr, "granmpm: %s\n", err.msg);
    return MPM_APP_EXIT_USAGE;
  }
  if (o->outdir) {
    if (strlen(o->outdir) >= sizeof cfg->output.dir)
      return mpm_app_usage("--output '%s': path too long", o->outdir);
    strcpy(cfg->output.dir, o->outdir);
  }
  return 0;
}

/* A nonlocal model whose explicit diffusion of g is unstable at the planned
 * time step and substeps: a warning on stderr, not an error (MODEL.md section
 * 5). The implicit diffusion has no such limit. */
static void warn_diffusion(const char *file, const mpm_config *cfg)
{
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
  if (mpm_material_ngf_check_diffusion(&par, dt, n_sub, cfg->mesh.dx, cfg->mesh.dy, &err) != MPM_OK)
    fprintf(stderr, "granmpm: warning: %s: %s (key 'material.n_sub')\n", file, err.msg);
}

static int cmd_check(int argc, char **argv)
{
  run_opts o;
  mpm_config cfg;
  int rc = parse_run_opts(argc, argv, 0, &o);
  if (rc == 0)
    rc = load_input(&o, &cfg);
  if (rc == 0) {
    mpm_io_input_write(stdout, &cfg);
    warn_diffusion(o.file, &cfg);
  }
  return rc;
}

/* ---- run ------------------------------------------------------------------ */

typedef struct run_ctx {
  mpm_io_output *out;
  int quiet, tty;
  long frames;
  double *ft, *fm;     /* time and region mass of every frame, for the flow rate */
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
    return mpm_err_set(err, MPM_ENOMEM, "frame %ld: out of memory", c->frames);
  c->frames++;
  return mpm_io_output_frame(c->out, s->pts, &d, err);
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

/* The resolved input as text, for the output attributes. */
static char *input_text(const mpm_config *cfg)
{
  char *buf = NULL;
  size_t len = 0;
  FILE *f = open_memstream(&buf, &len);
  if (!f)
    return NULL;
  mpm_io_input_write(f, cfg);
  fclose(f);
  return buf;
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
  fprintf(stderr, "granmpm: flow rate Q = %.6g kg/(m s) from %zu frames with %g <= mass <= %g "
          "kg/m\n", q, n, cfg->region.m_lo, cfg->region.m_hi);
  char path[MPM_PATH_MAX + 32];
  snprintf(path, sizeof path, "%s/flow-rate.txt", cfg->output.dir);
  FILE *f = fopen(path, "w");
  if (!f)
    return mpm_err_set(err, MPM_EIO, "%s: cannot write", path);
  fprintf(f, "%.10g %zu %.10g %.10g\n", q, n, cfg->region.m_hi, cfg->region.m_lo);
  return fclose(f) == 0 ? MPM_OK : mpm_err_set(err, MPM_EIO, "%s: cannot write", path);
}

static int cmd_run(int argc, char **argv, int full_argc, char **full_argv)
{
  run_opts o;
  mpm_config cfg;
  int rc = parse_run_opts(argc, argv, 1, &o);
  if (rc == 0)
    rc = load_input(&o, &cfg);
  if (rc != 0)
    return rc;

  warn_diffusion(o.file, &cfg);
  mpm_err err = {0};
  mpm_sim *sim = NULL;
  if (mpm_sim_create(&sim, &cfg, &err) != MPM_OK) {
    fprintf(stderr, "granmpm: %s: %s\n", o.file, err.msg);
    return err.code == MPM_ENOMEM ? MPM_APP_EXIT_RUNTIME : MPM_APP_EXIT_USAGE;
  }
  run_ctx ctx = {.quiet = o.quiet, .tty = isatty(STDERR_FILENO)};
  char *cmdline = join_args(full_argc, full_argv), *text = input_text(&cfg);
  int st = mpm_io_output_open(&ctx.out, cfg.output.dir, cmdline, text, &sim->mesh, &err);
  free(cmdline);
  free(text);
  if (st == MPM_OK)
    st = mpm_sim_run(sim, on_frame, on_progress, &ctx, &err);
  if (ctx.tty && !ctx.quiet)
    fputc('\n', stderr);
  mpm_err cerr = {0};
  if (mpm_io_output_close(ctx.out, &cerr) != MPM_OK && st == MPM_OK) {
    st = cerr.code;
    err = cerr;
  }
  if (st != MPM_OK) {
    fprintf(stderr, "granmpm: %s\n", err.msg);
  } else if (sim->stop == MPM_STOP_KE) {  /* said even with --quiet: the run ended early */
    fprintf(stderr, "granmpm: stopped at t = %.6g s (before t_end = %.6g s): kinetic energy "
            "per unit mass %.3g J/kg < stop.ke = %.3g J/kg\n", sim->t, cfg.time.t_end,
            sim->stop_value, cfg.stop.ke);
  } else if (sim->stop == MPM_STOP_MASS) {
    fprintf(stderr, "granmpm: stopped at t = %.6g s (before t_end = %.6g s): mass in region "
            "%.6g kg/m < stop.mass = %.6g kg/m\n", sim->t, cfg.time.t_end, sim->stop_value,
            cfg.stop.mass);
  }
  if (st == MPM_OK && cfg.region.m_hi > 0.0)
    st = report_flow_rate(&ctx, &cfg, &err);
  if (st == MPM_OK && !o.quiet) {
    fprintf(stderr, "granmpm: %ld steps of %.4g s, %ld frames, %zu points -> %s/run.h5\n",
            sim->step, sim->dt, ctx.frames, sim->pts->n, cfg.output.dir);
  }
  mpm_sim_free(sim);
  free(ctx.ft);
  free(ctx.fm);
  return st == MPM_OK ? 0 : MPM_APP_EXIT_RUNTIME;
}

/* ---- extract --------------------------------------------------------------- */

static int cmd_extract(int argc, char **argv)
{
  if (mpm_app_is_analysis(argc, argv))
    return mpm_app_analyse(argc, argv);
  const char *dir = NULL, *fields = NULL;
  int frame = -1;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    int st = 0;
    if (strcmp(a, "--frame") == 0 && v) {
      st = mpm_app_arg_frame("extract", v, &frame);
      i++;
    } else if (strcmp(a, "--fields") == 0 && v) {
      fields = v;
      i++;
    } else {
      st = mpm_app_arg_positional("extract", a, &dir, 1);
    }
    if (st != 0)
      return st;
  }
  if (!dir)
    return mpm_app_usage("%s: a run directory is required", "extract");
  mpm_err err = {0};
  if (mpm_io_extract(dir, frame, fields, stdout, &err) != MPM_OK)
    return mpm_app_fail(&err);
  return 0;
}

int main(int argc, char **argv)
{
  if (argc < 2)
    return mpm_app_usage("%s", "a command is required");
  const char *cmd = argv[1];
  if (strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0 || strcmp(cmd, "help") == 0) {
    fputs(usage_text, stdout);
    return 0;
  }
  if (strcmp(cmd, "--version") == 0) {
    printf("granmpm %s\n", PACKAGE_VERSION);
    return 0;
  }
  if (strcmp(cmd, "run") == 0)
    return cmd_run(argc - 1, argv + 1, argc, argv);
  if (strcmp(cmd, "check") == 0)
    return cmd_check(argc - 1, argv + 1);
  if (strcmp(cmd, "extract") == 0)
    return cmd_extract(argc - 1, argv + 1);
  if (strcmp(cmd, "state") == 0)
    return mpm_app_state(argc - 1, argv + 1);
  if (strcmp(cmd, "constitutive") == 0)
    return mpm_app_constitutive(argc - 1, argv + 1);
  return mpm_app_usage("unknown command '%s'", cmd);
}
