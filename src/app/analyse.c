/* analyse.c: `granmpm extract` measurements of a run directory
 * (docs/diagnostics.md): a frame's velocity profile across the depth, its
 * free surface, its points with nodally smoothed pressure ([DK15] eqs.
 * 4.1-4.3), a per-frame series of depth-averaged speed and acceleration,
 * mean mu of the flowing layer, front position and heap slope, the
 * silo classifier of [DK-silo] section 7.2 (static, flowing or unsure) or
 * its evidence frame by frame, and
 * the roughness of a frame's pressure with its dense fraction. Frames are
 * read back with io/frame.c; the numbers come from diag/flow.c. A 3D run is
 * measured on the x and y of its points (all of them, or those of a slab
 * --z-range ZMIN:ZMAX) over the x-y section of its box mesh; --smooth,
 * which needs the run's own 2D weights, takes 2D runs only. */
#define _POSIX_C_SOURCE 200809L
#include "app/analyse.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/args.h"
#include "diag/flow.h"
#include "diag/jam.h"
#include "diag/rough.h"
#include "io/io.h"
#include "shape/shape.h"

enum mode {
  MODE_NONE, MODE_PROFILE, MODE_SURFACE, MODE_SMOOTH, MODE_SERIES, MODE_JAM, MODE_JAM_SERIES,
  MODE_ROUGH
};

/* The options that ask for a measurement, by mode; --profile takes a value. */
static const char *const mode_option[] = {
  [MODE_PROFILE] = "--profile", [MODE_SURFACE] = "--surface", [MODE_SMOOTH] = "--smooth",
  [MODE_SERIES] = "--series", [MODE_JAM] = "--jam", [MODE_JAM_SERIES] = "--jam-series",
  [MODE_ROUGH] = "--roughness",
};

typedef struct opts {
  const char *dir;
  int mode;
  int frame;            /* < 0: last */
  int nbins;            /* --profile N */
  double ymin, ymax;    /* --range A:B (ymax <= ymin: 0 to the top point) */
  double width;         /* column width [m]; 0: mesh dx */
  double gdot_min;      /* flowing-layer threshold [1/s] */
  double front_cell;    /* 0: mesh dx */
  double radius;        /* --roughness neighbourhood [m]; 0: 1.5 mesh dx */
  int front_min;        /* 1: no filtering */
  int slope;            /* 0 none, 1 range, 2 auto */
  double xa, xb;
  int zsel;             /* --z-range given */
  double zmin, zmax;
} opts;

static int bad_value(const char *opt, const char *what, const char *v)
{
  return mpm_app_usage("extract: %s expects %s, got '%s'", opt, what, v);
}

/* "A:B" with finite A < B. */
static int pair(const char *s, double *a, double *b)
{
  return mpm_app_arg_pair(s, a, b);
}

/* Option a with the value v: -1 if a is no such option, else 0 or the usage
 * exit status. */
static int parse_valued(const char *a, const char *v, opts *o)
{
  const struct { const char *name; double *dst; int positive; const char *what; } real[] = {
    {"--width", &o->width, 1, "a column width > 0 [m]"},
    {"--gdot-min", &o->gdot_min, 0, "a shear rate >= 0 [1/s]"},
    {"--front-cell", &o->front_cell, 1, "a cell size > 0 [m]"},
    {"--radius", &o->radius, 1, "a radius > 0 [m]"},
  };
  const struct { const char *name; int *dst; int lo, hi; const char *what; } whole[] = {
    {"--profile", &o->nbins, 1, 100000, "a number of bins 1..100000"},
    {"--front-min", &o->front_min, 1, 1000, "a point count 1..1000"},
  };
  for (size_t k = 0; k < sizeof real / sizeof real[0]; k++)
    if (strcmp(a, real[k].name) == 0) {
      double d;
      if (!mpm_app_arg_real(v, &d) || d < 0.0 || (real[k].positive && !(d > 0.0)))
        return bad_value(a, real[k].what, v);
      *real[k].dst = d;
      return 0;
    }
  for (size_t k = 0; k < sizeof whole / sizeof whole[0]; k++)
    if (strcmp(a, whole[k].name) == 0)
      return mpm_app_arg_int(v, whole[k].lo, whole[k].hi, whole[k].dst)
                 ? 0 : bad_value(a, whole[k].what, v);
  if (strcmp(a, "--frame") == 0)
    return mpm_app_arg_frame("extract", v, &o->frame);
  if (strcmp(a, "--range") == 0)
    return pair(v, &o->ymin, &o->ymax) ? 0 : bad_value(a, "YMIN:YMAX with YMIN < YMAX", v);
  if (strcmp(a, "--z-range") == 0) {
    o->zsel = 1;
    return pair(v, &o->zmin, &o->zmax) ? 0 : bad_value(a, "ZMIN:ZMAX with ZMIN < ZMAX", v);
  }
  if (strcmp(a, "--slope") == 0) {
    if (strcmp(v, "auto") == 0)
      o->slope = 2;
    else if (pair(v, &o->xa, &o->xb))
      o->slope = 1;
    else
      return bad_value(a, "XA:XB with XA < XB or 'auto'", v);
    return 0;
  }
  return -1;
}

static int mode_of(const char *a)
{
  for (int m = MODE_PROFILE; m <= MODE_ROUGH; m++)
    if (strcmp(a, mode_option[m]) == 0)
      return m;
  return MODE_NONE;
}

static int parse(int argc, char **argv, opts *o)
{
  memset(o, 0, sizeof *o);
  o->frame = -1;
  o->front_min = 1;
  for (int i = 1; i < argc; i++) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    int m = mode_of(a), st = -1;
    if (m != MODE_NONE)
      o->mode = m;
    if (m != MODE_NONE && m != MODE_PROFILE)
      continue;
    if (v)
      st = parse_valued(a, v, o);
    if (st < 0)
      st = mpm_app_arg_positional("extract", a, &o->dir, 1);
    else
      i++;
    if (st != 0)
      return st;
  }
  if (!o->dir)
    return mpm_app_usage("extract: a run directory is required");
  return 0;
}

int mpm_app_is_analysis(int argc, char **argv)
{
  for (int i = 1; i < argc; i++)
    if (mode_of(argv[i]) != MODE_NONE)
      return 1;
  return 0;
}

/* ---- the measurements --------------------------------------------------------- */

/* Frame k (< 0: the last) of r into pts, with --z-range only the points of
 * the slab zmin <= z <= zmax (a 2D run has no z: MPM_EINPUT). */
static int read_frame(const opts *o, mpm_io_run *r, int k, mpm_points *pts, double *t,
                      mpm_err *err)
{
  int rc = mpm_io_run_frame(r, k, pts, t, err);
  if (rc != MPM_OK || !o->zsel)
    return rc;
  if (pts->dim != 3)
    return mpm_err_set(err, MPM_EINPUT, "--z-range: run '%s' is 2D, its points have no z",
                       o->dir);
  unsigned char *keep = malloc(pts->n + 1);
  if (!keep)
    return mpm_err_set(err, MPM_ENOMEM, "out of memory");
  for (size_t i = 0; i < pts->n; i++)
    keep[i] = pts->z[i] >= o->zmin && pts->z[i] <= o->zmax;
  mpm_points_compact(pts, keep);
  free(keep);
  return MPM_OK;
}

static int do_profile(const opts *o, const mpm_points *pts, const mpm_mesh *m, mpm_err *err)
{
  double ymin = o->ymin, ymax = o->ymax;
  if (!(ymax > ymin)) {                   /* default: mesh bottom to the top point */
    mpm_flow f;
    mpm_diag_flow(pts, 0.0, &f);
    ymin = m->y0;
    ymax = f.ymax;
  }
  mpm_profile_bin *b = malloc((size_t)o->nbins * sizeof *b);
  if (!b)
    return mpm_err_set(err, MPM_ENOMEM, "out of memory");
  int rc = mpm_diag_profile(pts, ymin, ymax, o->nbins, b, err);
  if (rc == MPM_OK) {
    printf("y,vx,vy,mass,n\n");
    for (int k = 0; k < o->nbins; k++)
      printf("%.10g,%.10g,%.10g,%.10g,%zu\n", b[k].y, b[k].vx, b[k].vy, b[k].mass, b[k].n);
  }
  free(b);
  return rc;
}

/* Columns of width w across the mesh, at most 1e7 of them. */
static int column_count(const mpm_mesh *m, double w, int *n, mpm_err *err)
{
  double c = ceil(m->lx / w);
  if (!(c >= 1.0 && c <= 1e7))
    return mpm_err_set(err, MPM_EINPUT, "--width %g: %g columns across the %g m mesh "
                       "(allowed: 1 ... 1e7)", w, c, m->lx);
  *n = (int)c;
  return MPM_OK;
}

static int do_surface(const opts *o, const mpm_points *pts, const mpm_mesh *m, mpm_err *err)
{
  double w = o->width > 0 ? o->width : m->dx;
  int n = 0, rc = column_count(m, w, &n, err);
  if (rc != MPM_OK)
    return rc;
  double *top = malloc((size_t)n * sizeof *top);
  if (!top)
    return mpm_err_set(err, MPM_ENOMEM, "out of memory");
  rc = mpm_diag_surface(pts, m->x0, w, n, top, err);
  if (rc == MPM_OK) {
    printf("x,top\n");
    for (int k = 0; k < n; k++)
      if (!isnan(top[k]))
        printf("%.10g,%.10g\n", m->x0 + (k + 0.5) * w, top[k]);
  }
  free(top);
  return rc;
}

static int do_smooth(const mpm_points *pts, const mpm_mesh *m, const char *shape, double t,
                     mpm_err *err)
{
  const mpm_shape_type *type = mpm_shape_lookup(shape);
  if (!type)
    return mpm_err_set(err, MPM_EINPUT, "run uses unknown shape functions '%s'", shape);
  mpm_shape_stencil *st = mpm_shape_stencil_alloc(pts->n);
  size_t n = pts->n, nn = (size_t)m->nnodes;
  double *p = malloc((n + 1) * sizeof *p), *ps = malloc((n + 1) * sizeof *ps);
  double *nm = malloc(nn * sizeof *nm), *nmf = malloc(nn * sizeof *nmf);
  int rc = (!st || !p || !ps || !nm || !nmf) ? mpm_err_set(err, MPM_ENOMEM, "out of memory")
                                             : MPM_OK;
  if (rc == MPM_OK) {
    mpm_diag_pressure(pts, p);
    rc = mpm_shape_stencil_compute(st, type, m, pts, t, err);
  }
  if (rc == MPM_OK)
    rc = mpm_diag_smooth(st, n, pts->mass, p, m->nnodes, nm, nmf, ps, err);
  if (rc == MPM_OK) {
    printf("x,y,p,p_smooth,gdot_p,state\n");
    for (size_t i = 0; i < n; i++)
      printf("%.10g,%.10g,%.10g,%.10g,%.10g,%d\n", pts->x[i], pts->y[i], p[i], ps[i],
             pts->gdp[i], pts->state[i]);
  }
  mpm_shape_stencil_free(st);
  free(p);
  free(ps);
  free(nm);
  free(nmf);
  return rc;
}

static int do_series(const opts *o, mpm_io_run *r, const mpm_mesh *m, mpm_err *err)
{
  int nf = mpm_io_run_nframes(r);
  double w = o->width > 0 ? o->width : m->dx, h = o->front_cell > 0 ? o->front_cell : m->dx;
  double *t = calloc((size_t)nf + 1, sizeof *t), *v = calloc((size_t)nf + 1, sizeof *v);
  double *a = calloc((size_t)nf + 1, sizeof *a);
  mpm_flow *f = calloc((size_t)nf + 1, sizeof *f);
  double *front = calloc((size_t)nf + 1, sizeof *front), *sl = calloc((size_t)nf + 1, sizeof *sl);
  double *xa = calloc((size_t)nf + 1, sizeof *xa), *xb = calloc((size_t)nf + 1, sizeof *xb);
  mpm_points *pts = mpm_points_alloc(0);
  int ncol = 0;
  int rc = (!t || !v || !a || !f || !front || !sl || !xa || !xb || !pts)
             ? mpm_err_set(err, MPM_ENOMEM, "out of memory") : MPM_OK;
  if (rc == MPM_OK && o->slope)
    rc = column_count(m, w, &ncol, err);   /* a bad --width is an error, not NaN slopes */
  for (int k = 0; rc == MPM_OK && k < nf; k++) {
    rc = read_frame(o, r, k, pts, &t[k], err);
    if (rc != MPM_OK)
      break;
    mpm_diag_flow(pts, o->gdot_min, &f[k]);
    v[k] = f[k].vx;
    rc = mpm_diag_front(pts, h, o->front_min, &front[k], err);
    sl[k] = NAN;
    if (rc == MPM_OK && o->slope) {
      xa[k] = o->xa;
      xb[k] = o->xb;
      int src = o->slope == 2
                    ? mpm_diag_slope_range(pts, m->x0, w, ncol, m->y0, &xa[k], &xb[k], err)
                    : MPM_OK;
      if (src == MPM_OK && mpm_diag_heap_slope(pts, xa[k], xb[k], w, &sl[k], err) != MPM_OK)
        sl[k] = NAN;                       /* no surface in range in this frame */
      if (src != MPM_OK)
        sl[k] = xa[k] = xb[k] = NAN;
    }
  }
  if (rc == MPM_OK && nf >= 2)
    rc = mpm_diag_derivative((size_t)nf, t, v, a, err);
  if (rc == MPM_OK) {
    printf("t,vx,speed,ax,mu,flow_mass,front%s\n", o->slope ? ",slope,slope_deg,xa,xb" : "");
    for (int k = 0; k < nf; k++) {
      printf("%.10g,%.10g,%.10g,%.10g,%.10g,%.10g,%.10g", t[k], v[k], f[k].speed, a[k],
             f[k].mu, f[k].flow_mass, front[k]);
      if (o->slope)
        printf(",%.10g,%.10g,%.10g,%.10g", sl[k], atan(fabs(sl[k])) * 180.0 / acos(-1.0),
               xa[k], xb[k]);
      printf("\n");
    }
  }
  mpm_points_free(pts);
  free(t);
  free(v);
  free(a);
  free(f);
  free(front);
  free(sl);
  free(xa);
  free(xb);
  return rc;
}

/* --roughness: the pressure roughness and dense fraction of one frame
 * (diag/rough.h), neighbours within 1.5 units (max(dx, dy)) unless --radius. */
static int do_rough(const opts *o, const mpm_points *pts, const mpm_mesh *m, double t,
                    mpm_err *err)
{
  const double r = o->radius > 0.0 ? o->radius : 1.5 * fmax(m->dx, m->dy);
  mpm_roughness q;
  int rc = mpm_diag_roughness(pts, r, &q, err);
  if (rc == MPM_OK) {
    printf("t,roughness,dense_fraction,mean_p,points,dense,counted,radius\n");
    printf("%.10g,%.6g,%.6g,%.8g,%zu,%zu,%zu,%.6g\n", t, q.roughness, q.dense_fraction,
           q.mean_p, q.npoints, q.ndense, q.nused, r);
  }
  return rc;
}

/* The ids of a frame lie below this (slots for matching points by id). */
static size_t id_bound(const mpm_points *pts)
{
  size_t b = 0;
  for (size_t p = 0; p < pts->n; p++)
    if (pts->id[p] >= 0 && (size_t)pts->id[p] + 1 > b)
      b = (size_t)pts->id[p] + 1;
  return b;
}

/* --jam: the mean vertical velocity the dense material moved with between
 * frames and the point count of every frame, classified (diag/jam.h); one
 * CSV row with the evidence. --jam-series: that evidence, one row a frame
 * (time, mean velocity, points, points gone since the frame before, dense
 * points). */
static int do_jam(const opts *o, mpm_io_run *r, mpm_err *err)
{
  const int nf = mpm_io_run_nframes(r);
  double *t = calloc((size_t)nf + 1, sizeof *t), *v = calloc((size_t)nf + 1, sizeof *v);
  size_t *n = calloc((size_t)nf + 1, sizeof *n), *nd = calloc((size_t)nf + 1, sizeof *nd);
  mpm_points *pts = mpm_points_alloc(0), *prev = mpm_points_alloc(0);
  int *slot = NULL;
  size_t nslot = 0;
  int rc = (!t || !v || !n || !nd || !pts || !prev)
               ? mpm_err_set(err, MPM_ENOMEM, "out of memory") : MPM_OK;
  for (int k = 0; rc == MPM_OK && k < nf; k++) {
    rc = read_frame(o, r, k, pts, &t[k], err);
    if (rc != MPM_OK)
      break;
    if (k == 0) {                            /* points only leave: frame 0 bounds the ids */
      nslot = id_bound(pts);
      if (!(slot = malloc((nslot ? nslot : 1) * sizeof *slot))) {
        rc = mpm_err_set(err, MPM_ENOMEM, "out of memory");
        break;
      }
      for (size_t i = 0; i < nslot; i++)
        slot[i] = -1;
      v[k] = NAN;
    } else {
      v[k] = mpm_diag_dense_vy_moved(prev, pts, t[k] - t[k - 1], slot, nslot);
    }
    n[k] = pts->n;
    for (size_t p = 0; p < pts->n; p++)
      nd[k] += pts->state[p] == MPM_STATE_DENSE;
    mpm_points *swap = prev;                 /* this frame becomes the previous one */
    prev = pts;
    pts = swap;
  }
  mpm_jam j;
  if (rc == MPM_OK)
    rc = mpm_diag_jam((size_t)nf, t, v, n, &j, err);  /* checks the frames either way */
  if (rc == MPM_OK && o->mode == MODE_JAM_SERIES) {
    printf("t,vbar,points,left,dense\n");
    for (int k = 0; k < nf; k++)
      printf("%.10g,%.6g,%zu,%zu,%zu\n", t[k], v[k], n[k], k ? n[k - 1] - n[k] : 0, nd[k]);
  } else if (rc == MPM_OK) {
    printf("class,t_zero,t_end,velocity_vote,leaving_per_frame,outflow_vote,frames\n");
    printf("%s,%.6g,%.6g,%s,%.6g,%s,%d\n", mpm_diag_jam_name(j.cls), j.t_zero, j.t_end,
           mpm_diag_jam_name(j.v_vote), j.leaving, mpm_diag_jam_name(j.n_vote), nf);
  }
  mpm_points_free(pts);
  mpm_points_free(prev);
  free(slot);
  free(t);
  free(v);
  free(n);
  free(nd);
  return rc;
}

int mpm_app_analyse(int argc, char **argv)
{
  opts o;
  int st = parse(argc, argv, &o);
  if (st != 0)
    return st;
  mpm_err err = {0};
  mpm_io_run *r = NULL;
  mpm_mesh m;
  char shape[64];
  double t = 0.0;
  mpm_points *pts = mpm_points_alloc(0);
  int rc = pts ? mpm_io_run_open(&r, o.dir, &err) : mpm_err_set(&err, MPM_ENOMEM, "out of memory");
  if (rc == MPM_OK)
    rc = mpm_io_run_mesh(r, &m, shape, sizeof shape, &err);
  if (rc == MPM_OK && o.mode == MODE_SMOOTH && mpm_io_run_dim(r) != 2)
    rc = mpm_err_set(&err, MPM_EINPUT, "--smooth: run '%s' is 3D; the smoothing takes a 2D "
                     "run's own weights", o.dir);
  if (rc == MPM_OK && o.mode != MODE_SERIES && o.mode != MODE_JAM && o.mode != MODE_JAM_SERIES)
    rc = read_frame(&o, r, o.frame, pts, &t, &err);
  if (rc == MPM_OK) {
    switch (o.mode) {
    case MODE_PROFILE: rc = do_profile(&o, pts, &m, &err); break;
    case MODE_SURFACE: rc = do_surface(&o, pts, &m, &err); break;
    case MODE_SMOOTH: rc = do_smooth(pts, &m, shape, t, &err); break;
    case MODE_JAM:
    case MODE_JAM_SERIES: rc = do_jam(&o, r, &err); break;
    case MODE_ROUGH: rc = do_rough(&o, pts, &m, t, &err); break;
    default: rc = do_series(&o, r, &m, &err); break;
    }
  }
  mpm_io_run_close(r);
  mpm_points_free(pts);
  if (rc != MPM_OK)
    return mpm_app_fail(&err);
  return fflush(stdout) == 0 ? 0 : MPM_APP_EXIT_RUNTIME;
}
