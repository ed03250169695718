/* shape.c: the shape-variant registry and the per-point stencil
 * (MODEL.md section 3, step 1 of section 2).
 *
 * The stencil stores, for point p, count[p] nodes in slots
 * [p w, p w + count[p]) of node, S, dSx, dSy, w the width the shape's span
 * gives for the points (4 for Q4 delta weights, 9 for uGIMP extents of half a
 * unit or less, at most MPM_STENCIL_W), and the unit row of its centre.
 * Points are independent, so the loop runs in parallel; a point outside the
 * mesh is reported after the loop (the first one in point order). */
#include "shape/shape.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

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

int mpm_shape_stencil_reserve(mpm_shape_stencil *st, size_t cap, int w, int dim)
{
  if (cap == 0)
    cap = 1;
  if (w < 1 || cap > SIZE_MAX / ((size_t)w * sizeof(double)))
    return MPM_ENOMEM;
  const size_t slots = cap * (size_t)w;
  if (cap > st->cap || !st->count) {
    if (grow((void **)&st->count, cap, sizeof *st->count) != MPM_OK ||
        grow((void **)&st->row, cap, sizeof *st->row) != MPM_OK)
      return MPM_ENOMEM;
  }
  if (slots > st->wcap || !st->node || (dim == 3 && !st->dSz)) {
    if (grow((void **)&st->node, slots, sizeof *st->node) != MPM_OK ||
        grow((void **)&st->S, slots, sizeof *st->S) != MPM_OK ||
        grow((void **)&st->dSx, slots, sizeof *st->dSx) != MPM_OK ||
        grow((void **)&st->dSy, slots, sizeof *st->dSy) != MPM_OK ||
        (dim == 3 && grow((void **)&st->dSz, slots, sizeof *st->dSz) != MPM_OK))
      return MPM_ENOMEM;
    st->wcap = slots;
  }
  if (cap > st->cap)
    st->cap = cap;
  st->w = w;
  return MPM_OK;
}

mpm_shape_stencil *mpm_shape_stencil_alloc(size_t cap)
{
  mpm_shape_stencil *st = calloc(1, sizeof *st);
  if (!st)
    return NULL;
  if (cap > 0 && mpm_shape_stencil_reserve(st, cap, MPM_STENCIL_W, 2) != MPM_OK) {
    mpm_shape_stencil_free(st);
    return NULL;
  }
  st->w = MPM_STENCIL_W;
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
  free(st->dSx);
  free(st->dSy);
  free(st->dSz);
  free(st);
}

/* The stencil of points [lo, hi) by the shape's eval, point by point (the
 * contract of mpm_shape_type.fill). */
static long eval_range(const mpm_shape_type *type, const mpm_mesh *m, const mpm_points *pts,
                       long lo, long hi, mpm_shape_stencil *st)
{
  const size_t w = (size_t)st->w;
  long first = hi;
  for (long p = lo; p < hi; p++) {
    const double r[4] = {pts->r1x[p], pts->r1y[p], pts->r2x[p], pts->r2y[p]};
    const size_t o = (size_t)p * w;
    const int c = type->eval(m, pts->x[p], pts->y[p], r, st->node + o, st->S + o, st->dSx + o,
                             st->dSy + o);
    if (mpm_shape_stencil_point(m, st, p, pts->y[p], c) < 0 && p < first)
      first = p;
  }
  return first;
}

/* Evaluate every point, in chunks of consecutive points (independent, so
 * the chunks run in parallel); returns the index of the first one outside,
 * or n. */
static long stencil_fill(mpm_shape_stencil *st, const mpm_shape_type *type, const mpm_mesh *m,
                         const mpm_points *pts)
{
  enum { CHUNK = 512 };
  const long n = (long)pts->n, nchunk = (n + CHUNK - 1) / CHUNK;
  long first = n;
#ifdef _OPENMP
#pragma omp parallel for schedule(static) reduction(min : first)
#endif
  for (long k = 0; k < nchunk; k++) {
    const long lo = k * CHUNK, hi = lo + CHUNK < n ? lo + CHUNK : n;
    const long f =
        type->fill ? type->fill(m, pts, lo, hi, st) : eval_range(type, m, pts, lo, hi, st);
    if (f < hi && f < first)
      first = f;
  }
  return first;
}

int mpm_shape_stencil_compute(mpm_shape_stencil *st, const mpm_shape_type *type, const mpm_mesh *m,
                              const mpm_points *pts, double t, mpm_err *err)
{
  if (!st || !type || !m || !pts)
    return mpm_err_set(err, MPM_EINVAL, "stencil: missing stencil, shape, "
                       "mesh or points");
  int w, reach;
  type->span(m, pts, &w, &reach);
  if (mpm_shape_stencil_reserve(st, pts->n, w, 2) != MPM_OK)
    return mpm_err_set(err, MPM_ENOMEM, "stencil for %zu points: out of memory",
                       pts->n);
  st->reach = reach;
  const long bad = stencil_fill(st, type, m, pts);
  if (bad < (long)pts->n)
    return mpm_err_set(err, MPM_EOUTSIDE,
                       "point %d left the mesh at (%.6g, %.6g) m, t = %.6g s "
                       "(mesh [%g, %g] x [%g, %g] m)",
                       pts->id[bad], pts->x[bad], pts->y[bad], t, m->x0,
                       m->x0 + m->lx, m->y0, m->y0 + m->ly);
  return MPM_OK;
}
