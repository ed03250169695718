/* constitutive.c: `granmpm constitutive`, one material point driven by a
 * velocity-gradient history (docs/constitutive-driver.md).
 *
 * Runs the model's stress update (MODEL.md section 4) at a chosen dt and the
 * ODE reference (GSL rkf45) at the same times, and writes both as CSV; or, with
 * --converge, runs the update over a dt sequence and prints for every field
 * "order NAME VALUE" and "error NAME VALUE" (relative time-integrated L2 error
 * at the finest dt). The numerics live in src/pointrun/ (history.h, series.h,
 * pointrun.h, reference.h), the history CSV in src/io/history.h; this file
 * parses arguments and prints. */
#include "app/constitutive.h"

#include "app/args.h"

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/config.h"
#include "io/history.h"
#include "io/io.h"
#include "material/material.h"
#include "pointrun/history.h"
#include "pointrun/pointrun.h"
#include "pointrun/reference.h"
#include "pointrun/series.h"

enum { MAX_SET = 64, MAX_DT = 32 };

static const char help_text[] =
  "usage: granmpm constitutive [FILE] [options]\n"
  "\n"
  "Drive one material point through a velocity-gradient history with the\n"
  "model's stress update and with the rkf45 reference ODE; write both as CSV.\n"
  "\n"
  "  FILE                  input file whose material section is used; without it\n"
  "                        the [DK15] App. B material (E = 1e4 Pa, nu = 0.3, mu_s = 0.3819,\n"
  "                        mu_2 = 0.6435, I0 = 0.279, d = 0.005 m, rho_s = 2450, rho_c = 1500)\n"
  "  --set material.KEY=V  override a material key (repeatable; with FILE any key)\n"
  "  --history dk15|CSV    velocity-gradient history: the built-in [DK15] App. B one\n"
  "                        (default) or a CSV file with columns t,Lxx,Lxy,Lyx,Lyy\n"
  "  --dt DT               time step of the update [s] (default 1e-3)\n"
  "  --sample mean|start|mid|end\n"
  "                        L used for a step: exact mean over the step (default), or\n"
  "                        L at its start, middle or end\n"
  "  --sigma0 SXX,SYY,SZZ,SXY  initial stress [Pa] (default 0)\n"
  "  --p0 P                initial stress -P I [Pa] (instead of --sigma0)\n"
  "  --rho0 RHO            initial density [kg/m^3] (default rho_c)\n"
  "  --rtol R, --atol A    reference tolerances (default 1e-10, 1e-9 Pa)\n"
  "  --no-reference        only the update (any model)\n"
  "  --output FILE         time-series CSV (default: standard output)\n"
  "  --every N             write every N-th step (default 1; the last row always)\n"
  "  --converge DT,DT,...  convergence mode: run the update at every dt and print\n"
  "                        'order NAME VALUE' and 'error NAME VALUE' per field\n"
  "  --table FILE          with --converge: CSV of the errors per dt\n"
  "  --write-history FILE  write the history as CSV and exit\n"
  "  --help\n";

typedef struct opts {
  const char *file, *history, *output, *table, *write_history;
  const char *sets[MAX_SET];
  int nset;
  double dt;
  int sample;
  int have_sigma0, have_p0, have_rho0, no_ref;
  mpm_sym3 sigma0;
  double p0, rho0, rtol, atol;
  long every;
  double conv_dt[MAX_DT];
  int nconv;
} opts;

/* Fields reported in convergence mode, in this order. mu = tau/p is left out:
 * it is 0/0 where the point reaches p = 0 (App. B ends there), and tau carries
 * the same information where it is defined. */
static const int conv_fields[] = {MPM_SER_SXX, MPM_SER_SYY, MPM_SER_SZZ, MPM_SER_SXY,
                                  MPM_SER_P, MPM_SER_TAU, MPM_SER_GDP};
enum { NCONV = sizeof conv_fields / sizeof conv_fields[0] };

static int usage(const char *fmt, const char *arg)
{
  fputs("granmpm constitutive: ", stderr);
  fprintf(stderr, fmt, arg);
  fputs(" (see 'granmpm constitutive --help')\n", stderr);
  return MPM_APP_EXIT_USAGE;
}

/* ------------------------------------------------------------ arguments */

/* Comma-separated list of up to max finite numbers; returns the count or -1. */
static int parse_list(const char *s, double *v, int max)
{
  int n = 0;
  const char *p = s;
  for (;;) {
    char *end;
    if (n == max)
      return -1;
    v[n] = strtod(p, &end);
    if (end == p || !isfinite(v[n]))
      return -1;
    n++;
    if (*end == '\0')
      return n;
    if (*end != ',')
      return -1;
    p = end + 1;
  }
}

static const char *next_arg(int argc, char **argv, int *i)
{
  return *i + 1 < argc ? argv[++*i] : NULL;
}

/* Options with a value; returns 0, or the exit status of a usage error. */
static int parse_valued(const char *a, const char *v, opts *o)
{
  double x[4];
  if (!v)
    return usage("option %s needs a value", a);
  if (strcmp(a, "--set") == 0) {
    if (o->nset == MAX_SET)
      return usage("too many %s options", a);
    o->sets[o->nset++] = v;
  } else if (strcmp(a, "--history") == 0) {
    o->history = v;
  } else if (strcmp(a, "--output") == 0) {
    o->output = v;
  } else if (strcmp(a, "--table") == 0) {
    o->table = v;
  } else if (strcmp(a, "--write-history") == 0) {
    o->write_history = v;
  } else if (strcmp(a, "--dt") == 0) {
    if (!mpm_app_arg_real(v, &o->dt) || !(o->dt > 0.0))
      return usage("--dt '%s': expected a time step > 0 s", v);
  } else if (strcmp(a, "--sample") == 0) {
    if ((o->sample = mpm_pointrun_sample_from_name(v)) < 0)
      return usage("--sample '%s': allowed: mean, start, mid, end", v);
  } else if (strcmp(a, "--sigma0") == 0) {
    if (parse_list(v, x, 4) != 4)
      return usage("--sigma0 '%s': expected 4 numbers SXX,SYY,SZZ,SXY [Pa]", v);
    o->sigma0 = (mpm_sym3){x[0], x[1], x[2], x[3], 0.0, 0.0};
    o->have_sigma0 = 1;
  } else if (strcmp(a, "--p0") == 0) {
    if (!mpm_app_arg_real(v, &o->p0))
      return usage("--p0 '%s': expected a pressure [Pa]", v);
    o->have_p0 = 1;
  } else if (strcmp(a, "--rho0") == 0) {
    if (!mpm_app_arg_real(v, &o->rho0) || !(o->rho0 > 0.0))
      return usage("--rho0 '%s': expected a density > 0 kg/m^3", v);
    o->have_rho0 = 1;
  } else if (strcmp(a, "--rtol") == 0) {
    if (!mpm_app_arg_real(v, &o->rtol) || !(o->rtol > 0.0))
      return usage("--rtol '%s': expected a tolerance > 0", v);
  } else if (strcmp(a, "--atol") == 0) {
    if (!mpm_app_arg_real(v, &o->atol) || !(o->atol > 0.0))
      return usage("--atol '%s': expected a tolerance > 0", v);
  } else if (strcmp(a, "--every") == 0) {
    int e;
    if (!mpm_app_arg_int(v, 1, 1000000000, &e))
      return usage("--every '%s': expected a whole number >= 1", v);
    o->every = e;
  } else if (strcmp(a, "--converge") == 0) {
    o->nconv = parse_list(v, o->conv_dt, MAX_DT);
    if (o->nconv < 2)
      return usage("--converge '%s': expected 2 or more time steps DT,DT,... (> 0 s)", v);
    for (int i = 0; i < o->nconv; i++)
      if (!(o->conv_dt[i] > 0.0))
        return usage("--converge '%s': time steps must be > 0 s", v);
  } else {
    return usage("unknown option '%s'", a);
  }
  return 0;
}

static int parse_args(int argc, char **argv, opts *o)
{
  memset(o, 0, sizeof *o);
  o->dt = 1e-3;
  o->every = 1;
  o->sample = MPM_SAMPLE_MEAN;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i];
    int rc = 0;
    if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
      fputs(help_text, stdout);
      return -1;
    } else if (strcmp(a, "--no-reference") == 0) {
      o->no_ref = 1;
    } else if (strncmp(a, "--", 2) == 0) {
      rc = parse_valued(a, next_arg(argc, argv, &i), o);
    } else if (a[0] == '-' && a[1] != '\0') {
      rc = usage("unknown option '%s'", a);
    } else if (!o->file) {
      o->file = a;
    } else {
      rc = usage("unexpected argument '%s'", a);
    }
    if (rc)
      return rc;
  }
  if (o->have_p0 && o->have_sigma0)
    return usage("%s: give either --p0 or --sigma0, not both", "--p0");
  if (o->nconv && o->no_ref)
    return usage("%s needs the reference (drop --no-reference)", "--converge");
  if (o->table && !o->nconv)
    return usage("%s is for --converge", "--table");
  return 0;
}

/* ------------------------------------------------------------ material */

/* The [DK15] App. B material: Table 1 with E = 1e4 Pa; xi = 1.1233 from I0, d, rho_s. */
static void dk15_material(mpm_config *cfg)
{
  snprintf(cfg->material.model, sizeof cfg->material.model, "%s", "mu_i");
  mpm_material_config_dk15(cfg);
  cfg->material.E = 1e4;
  cfg->material.A = 0.48;
  cfg->material.t0 = 1e-3;
}

/* "material.KEY=VALUE" applied to the built-in material (no input file). */
static int apply_set(const char *s, mpm_config *cfg)
{
  static const struct { const char *key; size_t off; } keys[] = {
    {"E", offsetof(mpm_config, material.E)},       {"nu", offsetof(mpm_config, material.nu)},
    {"rho_s", offsetof(mpm_config, material.rho_s)}, {"rho_c", offsetof(mpm_config, material.rho_c)},
    {"mu_s", offsetof(mpm_config, material.mu_s)}, {"mu_2", offsetof(mpm_config, material.mu_2)},
    {"I0", offsetof(mpm_config, material.I0)},     {"d", offsetof(mpm_config, material.d)},
    {"A", offsetof(mpm_config, material.A)},       {"t0", offsetof(mpm_config, material.t0)},
  };
  const char *eq = strchr(s, '=');
  if (strncmp(s, "material.", 9) != 0 || !eq)
    return usage("--set '%s': without an input file only material.KEY=VALUE is allowed", s);
  const char *key = s + 9, *val = eq + 1;
  size_t klen = (size_t)(eq - key);
  if (klen == 5 && strncmp(key, "model", 5) == 0) {
    if (!mpm_material_lookup(val) || strlen(val) >= sizeof cfg->material.model) {
      fprintf(stderr, "granmpm constitutive: --set '%s': unknown model (allowed:", s);
      for (int k = 0; mpm_material_table[k]; k++)
        fprintf(stderr, "%s %s", k ? "," : "", mpm_material_table[k]->name);
      fputs(") (see 'granmpm constitutive --help')\n", stderr);
      return MPM_APP_EXIT_USAGE;
    }
    snprintf(cfg->material.model, sizeof cfg->material.model, "%s", val);
    return 0;
  }
  for (size_t i = 0; i < sizeof keys / sizeof keys[0]; i++) {
    if (strlen(keys[i].key) != klen || strncmp(key, keys[i].key, klen) != 0)
      continue;
    double v;
    if (!mpm_app_arg_real(val, &v))
      return usage("--set '%s': expected a number", s);
    *(double *)(void *)((char *)cfg + keys[i].off) = v;
    return 0;
  }
  return usage("--set '%s': unknown key (allowed: material.model, E, nu, rho_s, rho_c, "
               "mu_s, mu_2, I0, d, A, t0)", s);
}

static int load_material(const opts *o, const mpm_material_type **mt, mpm_material_params *par)
{
  mpm_config cfg;
  memset(&cfg, 0, sizeof cfg);
  if (o->file) {
    mpm_err err = {0};
    if (mpm_io_input_load(o->file, o->sets, o->nset, &cfg, &err) != MPM_OK) {
      fprintf(stderr, "granmpm constitutive: %s\n", err.msg);
      return MPM_APP_EXIT_USAGE;
    }
  } else {
    dk15_material(&cfg);
    for (int i = 0; i < o->nset; i++)
      if (apply_set(o->sets[i], &cfg))
        return MPM_APP_EXIT_USAGE;
  }
  *mt = mpm_material_lookup(cfg.material.model);
  if (!*mt)
    return usage("unknown material model '%s'", cfg.material.model);
  mpm_material_params_from_config(par, &cfg);
  mpm_err err = {0};
  if ((*mt)->check && (*mt)->check(par, &err) != MPM_OK) {
    fprintf(stderr, "granmpm constitutive: %s%s%s\n", o->file ? o->file : "",
            o->file ? ": " : "", err.msg);
    return MPM_APP_EXIT_USAGE;
  }
  if (!o->no_ref && strcmp((*mt)->name, "mu_i") != 0)
    return usage("the reference ODE is the mu(I) law; model '%s' needs --no-reference",
                 (*mt)->name);
  return 0;
}

/* ------------------------------------------------------------ output */

static void write_header(FILE *f, int with_ref)
{
  fputs("t,Lxx,Lxy,Lyx,Lyy", f);
  for (int k = 0; k < MPM_SER_N; k++)
    fprintf(f, ",%s", mpm_pointrun_series_name(k));
  for (int k = 0; with_ref && k < MPM_SER_N; k++)
    fprintf(f, ",ref_%s", mpm_pointrun_series_name(k));
  fputc('\n', f);
}

static void write_row(FILE *f, const mpm_history *h, const mpm_series *a,
                      const mpm_series *r, size_t k)
{
  mpm_mat3 L = mpm_pointrun_history_eval(h, a->t[k]);
  fprintf(f, "%.10g,%.10g,%.10g,%.10g,%.10g", a->t[k], L.m[0][0], L.m[0][1], L.m[1][0],
          L.m[1][1]);
  for (int c = 0; c < MPM_SER_N; c++)
    fprintf(f, ",%.12g", mpm_pointrun_series_at(a, c, k) + 0.0);  /* + 0.0: no "-0" */
  for (int c = 0; r && c < MPM_SER_N; c++)
    fprintf(f, ",%.12g", mpm_pointrun_series_at(r, c, k) + 0.0);
  fputc('\n', f);
}

static int write_series(const opts *o, const mpm_history *h, const mpm_series *a,
                        const mpm_series *r)
{
  FILE *f = o->output ? fopen(o->output, "w") : stdout;
  if (!f) {
    fprintf(stderr, "granmpm constitutive: %s: cannot open for writing\n", o->output);
    return MPM_APP_EXIT_RUNTIME;
  }
  write_header(f, r != NULL);
  for (size_t k = 0; k < a->n; k++)
    if (k % (size_t)o->every == 0 || k + 1 == a->n)
      write_row(f, h, a, r, k);
  int bad = ferror(f);
  if (f != stdout)
    bad |= fclose(f) != 0;
  else
    bad |= fflush(f) != 0;
  if (bad) {
    fprintf(stderr, "granmpm constitutive: %s: write error\n", o->output ? o->output : "stdout");
    return MPM_APP_EXIT_RUNTIME;
  }
  return 0;
}

/* ------------------------------------------------------------ runs */

typedef struct problem {
  const mpm_material_type *mt;
  mpm_material_params par;
  mpm_history *h;
  mpm_point_init init;
  mpm_reference_opts ropt;
} problem;

/* Our update at dt and (unless ref is NULL) the reference at the same times. */
static int run_pair(const problem *pb, double dt, int sample, mpm_series **ours,
                    mpm_series **ref)
{
  mpm_err err = {0};
  if (mpm_pointrun_update(pb->mt, &pb->par, pb->h, &pb->init, dt, sample, ours, &err)
      != MPM_OK) {
    fprintf(stderr, "granmpm constitutive: %s\n", err.msg);
    return MPM_APP_EXIT_RUNTIME;
  }
  if (!ref)
    return 0;
  *ref = mpm_pointrun_series_alloc((*ours)->n);
  if (!*ref) {
    fputs("granmpm constitutive: out of memory\n", stderr);
    return MPM_APP_EXIT_RUNTIME;
  }
  memcpy((*ref)->t, (*ours)->t, (*ours)->n * sizeof *(*ours)->t);
  if (mpm_pointrun_reference_run(&pb->par, pb->h, &pb->init, &pb->ropt, *ref, &err) != MPM_OK) {
    fprintf(stderr, "granmpm constitutive: %s\n", err.msg);
    return MPM_APP_EXIT_RUNTIME;
  }
  return 0;
}

static int run_single(const opts *o, const problem *pb)
{
  mpm_series *a = NULL, *r = NULL;
  int rc = run_pair(pb, o->dt, o->sample, &a, o->no_ref ? NULL : &r);
  if (rc == 0)
    rc = write_series(o, pb->h, a, r);
  mpm_pointrun_series_free(a);
  mpm_pointrun_series_free(r);
  return rc;
}

static int write_table(const char *path, const opts *o, double err[][NCONV])
{
  FILE *f = fopen(path, "w");
  if (!f) {
    fprintf(stderr, "granmpm constitutive: %s: cannot open for writing\n", path);
    return MPM_APP_EXIT_RUNTIME;
  }
  fputs("dt", f);
  for (int c = 0; c < NCONV; c++)
    fprintf(f, ",%s", mpm_pointrun_series_name(conv_fields[c]));
  fputc('\n', f);
  for (int i = 0; i < o->nconv; i++) {
    fprintf(f, "%.6g", o->conv_dt[i]);
    for (int c = 0; c < NCONV; c++)
      fprintf(f, ",%.6e", err[i][c]);
    fputc('\n', f);
  }
  if (fclose(f) != 0) {
    fprintf(stderr, "granmpm constitutive: %s: write error\n", path);
    return MPM_APP_EXIT_RUNTIME;
  }
  return 0;
}

static void print_convergence(const opts *o, double err[][NCONV])
{
  int fine = 0;
  printf("# relative time-integrated L2 error against the rkf45 reference\n# %-10s", "dt");
  for (int c = 0; c < NCONV; c++)
    printf(" %12s", mpm_pointrun_series_name(conv_fields[c]));
  putchar('\n');
  for (int i = 0; i < o->nconv; i++) {
    printf("# %-10.4g", o->conv_dt[i]);
    for (int c = 0; c < NCONV; c++)
      printf(" %12.4e", err[i][c]);
    putchar('\n');
    if (o->conv_dt[i] < o->conv_dt[fine])
      fine = i;
  }
  for (int c = 0; c < NCONV; c++) {
    double e[MAX_DT];
    for (int i = 0; i < o->nconv; i++)
      e[i] = err[i][c];
    printf("order %s %.4f\n", mpm_pointrun_series_name(conv_fields[c]),
           mpm_pointrun_order(o->conv_dt, e, o->nconv));
  }
  for (int c = 0; c < NCONV; c++)
    printf("error %s %.4e\n", mpm_pointrun_series_name(conv_fields[c]), err[fine][c]);
}

static int run_convergence(const opts *o, const problem *pb)
{
  double err[MAX_DT][NCONV];
  for (int i = 0; i < o->nconv; i++) {
    mpm_series *a = NULL, *r = NULL;
    int rc = run_pair(pb, o->conv_dt[i], o->sample, &a, &r);
    for (int c = 0; rc == 0 && c < NCONV; c++)
      err[i][c] = mpm_pointrun_series_relerr(a, r, conv_fields[c]);
    mpm_pointrun_series_free(a);
    mpm_pointrun_series_free(r);
    if (rc)
      return rc;
  }
  print_convergence(o, err);
  if (fflush(stdout) != 0)
    return MPM_APP_EXIT_RUNTIME;
  return o->table ? write_table(o->table, o, err) : 0;
}

/* ------------------------------------------------------------ entry */

static int load_history(const opts *o, mpm_history **h)
{
  mpm_err err = {0};
  int rc = (!o->history || strcmp(o->history, "dk15") == 0)
               ? mpm_pointrun_history_dk15(h, &err) : mpm_io_history_read(o->history, h, &err);
  if (rc != MPM_OK) {
    fprintf(stderr, "granmpm constitutive: %s\n", err.msg);
    return rc == MPM_ENOMEM ? MPM_APP_EXIT_RUNTIME : MPM_APP_EXIT_USAGE;
  }
  return 0;
}

static int write_history_file(const char *path, const mpm_history *h)
{
  FILE *f = strcmp(path, "-") == 0 ? stdout : fopen(path, "w");
  if (!f) {
    fprintf(stderr, "granmpm constitutive: %s: cannot open for writing\n", path);
    return MPM_APP_EXIT_RUNTIME;
  }
  int bad = mpm_io_history_write(f, h) != MPM_OK;
  bad |= (f == stdout ? fflush(f) : fclose(f)) != 0;
  if (bad)
    fprintf(stderr, "granmpm constitutive: %s: write error\n", path);
  return bad ? MPM_APP_EXIT_RUNTIME : 0;
}

static void set_initial(const opts *o, problem *pb)
{
  pb->init.sigma = o->have_sigma0 ? o->sigma0
                   : o->have_p0   ? (mpm_sym3){-o->p0, -o->p0, -o->p0, 0.0, 0.0, 0.0}
                                  : mpm_sym3_zero();
  pb->init.rho = o->have_rho0 ? o->rho0 : pb->par.rho_c;
  mpm_pointrun_reference_defaults(&pb->par, &pb->ropt);
  if (o->rtol > 0.0)
    pb->ropt.rtol = o->rtol;
  if (o->atol > 0.0)
    pb->ropt.atol = o->atol;
}

int mpm_app_constitutive(int argc, char **argv)
{
  opts o;
  problem pb;
  memset(&pb, 0, sizeof pb);
  int rc = parse_args(argc, argv, &o);
  if (rc)
    return rc < 0 ? 0 : rc;
  rc = load_history(&o, &pb.h);
  if (rc == 0 && o.write_history) {
    rc = write_history_file(o.write_history, pb.h);
    mpm_pointrun_history_free(pb.h);
    return rc;
  }
  if (rc == 0)
    rc = load_material(&o, &pb.mt, &pb.par);
  if (rc == 0) {
    set_initial(&o, &pb);
    rc = o.nconv ? run_convergence(&o, &pb) : run_single(&o, &pb);
  }
  mpm_pointrun_history_free(pb.h);
  return rc;
}
