/* shape.c: the shape-variant registry and the per-point stencil
 * (MODEL.md section 3, step 1 of section 2).
 *
 * The stencil stores, for point p, count[p] nodes in slots
 * [p w, p w + count[p]) of node, S, dS[d], w the width the shape's span
 * gives for the points (4 for Q4 delta weights, 9 for plane uGIMP extents
 * of half a unit or less, 27 on boxes, at most mpm_shape_width_cap), or, on
 * boxes for a separable shape whose points all have extents along the axes,
 * their weights factorised by axis; and the unit along the last axis of its
 * centre. Points are independent, so the loop runs in parallel; a point
 * outside the mesh is reported after the loop (the first one in point
 * order). */
#include "shape/shape.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "shape/corners.h"

const mpm_shape_type *const mpm_shape_table[] = {
  &mpm_shape_delta,
  &mpm_shape_ugimp,
  &mpm_shape_cpdi,
  NULL
};

const mpm_shape_type *mpm_shape_lookup(const char *name)
{
  if (!name)
    return NULL;
  for (const mpm_shape_type *const *t = mpm_shape_table; *t; t++)
    if (strcmp((*t)->name, name) == 0)
      return *t;
  return NULL;
}

/* Grow one array to n elements of size sz (contents need not survive). */
static int grow(void **a, size_t n, size_t sz)
{
  void *p = realloc(*a, n * sz);
  if (!p)
    return MPM_ENOMEM;
  *a = p;
  return MPM_OK;
}

/* Room for count and row of cap points. */
static int reserve_points(mpm_shape_stencil *st, size_t cap)
{
  if (cap == 0)
    cap = 1;
  if (cap > st->cap || !st->count) {
    if (grow((void **)&st->count, cap, sizeof *st->count) != MPM_OK ||
        grow((void **)&st->row, cap, sizeof *st->row) != MPM_OK)
      return MPM_ENOMEM;
    st->cap = cap;
  }
  return MPM_OK;
}

int mpm_shape_stencil_reserve(mpm_shape_stencil *st, size_t cap, int w, int dim)
{
  if (cap == 0)
    cap = 1;
  if (w < 1 || cap > SIZE_MAX / ((size_t)w * sizeof(double)))
    return MPM_ENOMEM;
  if (reserve_points(st, cap) != MPM_OK)
    return MPM_ENOMEM;
  const size_t slots = cap * (size_t)w;
  if (slots > st->wcap || !st->node || (dim == 3 && !st->dS[2])) {
    if (grow((void **)&st->node, slots, sizeof *st->node) != MPM_OK ||
        grow((void **)&st->S, slots, sizeof *st->S) != MPM_OK ||
        grow((void **)&st->dS[0], slots, sizeof *st->dS[0]) != MPM_OK ||
        grow((void **)&st->dS[1], slots, sizeof *st->dS[1]) != MPM_OK ||
        (dim == 3 && grow((void **)&st->dS[2], slots, sizeof *st->dS[2]) != MPM_OK))
      return MPM_ENOMEM;
    st->wcap = slots;
  }
  st->w = w;
  st->dim = dim;
  return MPM_OK;
}

/* Room for the factorised weights of cap points. */
static int reserve_axes(mpm_shape_stencil *st, size_t cap)
{
  if (cap <= st->acap && st->axes)
    return MPM_OK;
  if (cap == 0)
    cap = 1;
  if (grow((void **)&st->axes, cap, sizeof *st->axes) != MPM_OK)
    return MPM_ENOMEM;
  st->acap = cap;
  return MPM_OK;
}

mpm_shape_stencil *mpm_shape_stencil_alloc(size_t cap)
{
  mpm_shape_stencil *st = calloc(1, sizeof *st);
  if (!st)
    return NULL;
  if (cap > 0 && mpm_shape_stencil_reserve(st, cap, 16, 2) != MPM_OK) {
    mpm_shape_stencil_free(st);
    return NULL;
  }
  st->w = 16;
  return st;
}

void mpm_shape_stencil_free(mpm_shape_stencil *st)
{
  if (!st)
    return;
  free(st->count);
  free(st->row);
  free(st->node);
  free(st->S);
  for (int d = 0; d < 3; d++)
    free(st->dS[d]);
  free(st->axes);
  free(st);
}

/* The stencil of points [lo, hi) by the shape's eval, point by point (the
 * contract of mpm_shape_type.fill). */
static long eval_range(const mpm_shape_type *type, const mpm_mesh *m, const mpm_points *pts,
                       long lo, long hi, mpm_shape_stencil *st)
{
  const size_t w = (size_t)st->w;
  const int D = m->dim, last = D - 1;
  long first = hi;
  for (long p = lo; p < hi; p++) {
    double r[9];
    mpm_shape_point_extent(pts, D, (size_t)p, r);
    const double x[3] = {pts->x[p], pts->y[p], D == 3 ? pts->z[p] : 0.0};
    const size_t o = (size_t)p * w;
    double *const dS[3] = {st->dS[0] + o, st->dS[1] + o, D == 3 ? st->dS[2] + o : NULL};
    const int c = type->eval(m, x, r, st->node + o, st->S + o, dS);
    if (mpm_shape_stencil_point(m, st, p, x[last], c) < 0 && p < first)
      first = p;
  }
  return first;
}

/* Evaluate every point, in chunks of consecutive points (independent, so
 * the chunks run in parallel); returns the index of the first one outside,
 * or n; with sep, the factorised form, *fits 0 if a point needs the list. */
static long stencil_fill(mpm_shape_stencil *st, const mpm_shape_type *type, const mpm_mesh *m,
                         const mpm_points *pts, int sep, int *fits)
{
  enum { CHUNK = 512 };
  const long n = (long)pts->n, nchunk = (n + CHUNK - 1) / CHUNK;
  long first = n;
  int ok = 1;
#ifdef _OPENMP
#pragma omp parallel for schedule(static) reduction(min : first) reduction(& : ok)
#endif
  for (long k = 0; k < nchunk; k++) {
    const long lo = k * CHUNK, hi = lo + CHUNK < n ? lo + CHUNK : n;
    long f;
    if (sep)
      f = mpm_shape_in_separable_range(m, pts, lo, hi, st, &ok);
    else
      f = type->fill && m->dim == 2 ? type->fill(m, pts, lo, hi, st)
                                    : eval_range(type, m, pts, lo, hi, st);
    if (f < hi && f < first)
      first = f;
  }
  *fits = ok;
  return first;
}

int mpm_shape_stencil_compute(mpm_shape_stencil *st, const mpm_shape_type *type, const mpm_mesh *m,
                              const mpm_points *pts, double t, mpm_err *err)
{
  if (!st || !type || !m || !pts)
    return mpm_err_set(err, MPM_EINVAL, "stencil: missing stencil, shape, "
                       "mesh or points");
  int w, reach, fits = 0;
  type->span(m, pts, &w, &reach);
  st->reach = reach;
  long bad = (long)pts->n;
  if (type->separable && m->dim == 3) {           /* factorised, if every point fits */
    if (reserve_axes(st, pts->n) != MPM_OK || reserve_points(st, pts->n) != MPM_OK)
      return mpm_err_set(err, MPM_ENOMEM, "stencil for %zu points: out of memory", pts->n);
    bad = stencil_fill(st, type, m, pts, 1, &fits);
    st->dim = m->dim;
  }
  st->sep = fits;
  if (!fits) {
    if (mpm_shape_stencil_reserve(st, pts->n, w, m->dim) != MPM_OK)
      return mpm_err_set(err, MPM_ENOMEM, "stencil for %zu points: out of memory", pts->n);
    bad = stencil_fill(st, type, m, pts, 0, &fits);
  }
  if (bad < (long)pts->n) {
    char z[48] = "", mz[48] = "";
    if (m->dim == 3) {
      snprintf(z, sizeof z, ", %.6g", pts->z[bad]);
      snprintf(mz, sizeof mz, " x [%g, %g]", m->z0, m->z0 + m->lz);
    }
    return mpm_err_set(err, MPM_EOUTSIDE,
                       "point %d left the mesh at (%.6g, %.6g%s) m, t = %.6g s "
                       "(mesh [%g, %g] x [%g, %g]%s m)",
                       pts->id[bad], pts->x[bad], pts->y[bad], z, t, m->x0,
                       m->x0 + m->lx, m->y0, m->y0 + m->ly, mz);
  }
  return MPM_OK;
}

int mpm_shape_stencil_list(const mpm_shape_stencil *st, const mpm_mesh *m, size_t p, int *node,
                           double *S, double *const dS[3])
{
  if (st->sep)
    return mpm_shape_in_separable_list(m, &st->axes[p], node, S, dS);
  const size_t o = p * (size_t)st->w;
  const int c = st->count[p];
  for (int k = 0; k < c; k++) {
    node[k] = st->node[o + k];
    S[k] = st->S[o + k];
    for (int d = 0; d < m->dim; d++)
      dS[d][k] = st->dS[d][o + k];
  }
  return c;
}
