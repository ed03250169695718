/* points.c: structure-of-arrays point store.
 *
 * Every loop over the fields skips those the store lacks (mpm_points_has):
 * a 2D store's 3D arrays, and the deformation gradients of a store that
 * does not carry them, stay NULL. */
#include "core/points.h"

#include <stdlib.h>
#include <string.h>

mpm_points *mpm_points_alloc_dim(size_t cap, int dim)
{
  if (dim != 2 && dim != 3)
    return NULL;
  mpm_points *pts = calloc(1, sizeof *pts);
  if (!pts)
    return NULL;
  pts->dim = dim;
  if (mpm_points_reserve(pts, cap ? cap : 16) != MPM_OK) {
    mpm_points_free(pts);
    return NULL;
  }
  return pts;
}

mpm_points *mpm_points_alloc(size_t cap)
{
  return mpm_points_alloc_dim(cap, 2);
}

void mpm_points_free(mpm_points *pts)
{
  if (!pts)
    return;
#define MPM_POINT_FREE_(f, nm, d, u, dim) free(pts->f);
  MPM_POINT_REAL_FIELDS(MPM_POINT_FREE_)
  MPM_POINT_INT_FIELDS(MPM_POINT_FREE_)
#undef MPM_POINT_FREE_
  free(pts);
}

/* Grow one array to cap elements of size sz, zeroing the new tail. */
static int grow(void **a, size_t old, size_t cap, size_t sz)
{
  void *p = realloc(*a, cap * sz);
  if (!p)
    return MPM_ENOMEM;
  memset((char *)p + old * sz, 0, (cap - old) * sz);
  *a = p;
  return MPM_OK;
}

int mpm_points_reserve(mpm_points *pts, size_t cap)
{
  if (cap <= pts->cap)
    return MPM_OK;
  int rc = MPM_OK;
#define MPM_POINT_GROW_(f, nm, d, u, dim)                                        \
  if (rc == MPM_OK && mpm_points_has(pts, dim))                                 \
    rc = grow((void **)&pts->f, pts->cap, cap, sizeof *pts->f);
  MPM_POINT_REAL_FIELDS(MPM_POINT_GROW_)
  MPM_POINT_INT_FIELDS(MPM_POINT_GROW_)
#undef MPM_POINT_GROW_
  if (rc != MPM_OK)
    return rc;  /* arrays already grown stay valid; cap unchanged is safe */
  pts->cap = cap;
  return MPM_OK;
}

/* The arrays of kind K the store gains (on: zero for every point) or loses. */
static int set_kind(mpm_points *pts, int K, int on)
{
  int rc = MPM_OK;
#define MPM_POINT_KIND_(f, nm, d, u, kind)                                      \
  if ((kind) == K && on && rc == MPM_OK) {                                      \
    pts->f = calloc(pts->cap ? pts->cap : 1, sizeof *pts->f);                   \
    rc = pts->f ? MPM_OK : MPM_ENOMEM;                                          \
  } else if ((kind) == K && !on) {                                              \
    free(pts->f);                                                               \
    pts->f = NULL;                                                              \
  }
  MPM_POINT_REAL_FIELDS(MPM_POINT_KIND_)
  MPM_POINT_INT_FIELDS(MPM_POINT_KIND_)
#undef MPM_POINT_KIND_
  if (rc != MPM_OK)
    set_kind(pts, K, 0);    /* the arrays allocated so far freed */
  return rc;
}

int mpm_points_set_dim(mpm_points *pts, int dim)
{
  if (dim != 2 && dim != 3)
    return MPM_EINVAL;
  if (dim == pts->dim)
    return MPM_OK;
  const int rc = set_kind(pts, MPM_POINT_3D, dim == 3);
  if (rc == MPM_OK)
    pts->dim = dim;
  return rc;
}

int mpm_points_set_defgrad(mpm_points *pts, int on)
{
  on = on != 0;
  if (on == pts->defgrad)
    return MPM_OK;
  const int rc = set_kind(pts, MPM_POINT_DEFGRAD, on);
  if (rc != MPM_OK)
    return rc;
  pts->defgrad = on;
  for (int a = 0; on && a < 3; a++)            /* F = Fp = I */
    for (size_t p = 0; p < pts->cap; p++)
      pts->F[a][a][p] = pts->Fp[a][a][p] = 1.0;
  return MPM_OK;
}

int mpm_points_push(mpm_points *pts, size_t *idx)
{
  if (pts->n == pts->cap) {
    int rc = mpm_points_reserve(pts, 2 * pts->cap + 16);
    if (rc != MPM_OK)
      return rc;
  }
  size_t i = pts->n++;
#define MPM_POINT_ZERO_(f, nm, d, u, dim) \
  if (mpm_points_has(pts, dim)) pts->f[i] = 0;
  MPM_POINT_REAL_FIELDS(MPM_POINT_ZERO_)
  MPM_POINT_INT_FIELDS(MPM_POINT_ZERO_)
#undef MPM_POINT_ZERO_
  pts->id[i] = pts->next_id++;
  *idx = i;
  return MPM_OK;
}

int mpm_points_copy(mpm_points *dst, const mpm_points *src)
{
  int rc = mpm_points_set_dim(dst, src->dim);
  if (rc == MPM_OK)
    rc = mpm_points_set_defgrad(dst, src->defgrad);
  if (rc == MPM_OK)
    rc = mpm_points_reserve(dst, src->n);
  if (rc != MPM_OK)
    return rc;
#define MPM_POINT_COPY_(f, nm, d, u, dim) \
  if (src->n && mpm_points_has(src, dim)) memcpy(dst->f, src->f, src->n * sizeof *src->f);
  MPM_POINT_REAL_FIELDS(MPM_POINT_COPY_)
  MPM_POINT_INT_FIELDS(MPM_POINT_COPY_)
#undef MPM_POINT_COPY_
  dst->n = src->n;
  dst->next_id = src->next_id;
  return MPM_OK;
}

void mpm_points_compact(mpm_points *pts, const unsigned char *keep)
{
  size_t j = 0;
  for (size_t i = 0; i < pts->n; i++) {
    if (!keep[i])
      continue;
    if (j != i) {
#define MPM_POINT_MOVE_(f, nm, d, u, kind) \
  if (mpm_points_has(pts, kind)) pts->f[j] = pts->f[i];
      MPM_POINT_REAL_FIELDS(MPM_POINT_MOVE_)
      MPM_POINT_INT_FIELDS(MPM_POINT_MOVE_)
#undef MPM_POINT_MOVE_
    }
    j++;
  }
  pts->n = j;
}

void mpm_points_permute(mpm_points *pts, const int *order, void *scratch)
{
  const size_t n = pts->n;
  double *td = scratch;
  int *ti = scratch;
#define MPM_POINT_PERMUTE_(t, f, dim)                                    \
  if (mpm_points_has(pts, dim)) {                                        \
    for (size_t k = 0; k < n; k++)                                       \
      t[k] = pts->f[order[k]];                                           \
    memcpy(pts->f, t, n * sizeof *t);                                    \
  }
#define MPM_POINT_PERMUTE_REAL_(f, nm, d, u, dim) MPM_POINT_PERMUTE_(td, f, dim)
#define MPM_POINT_PERMUTE_INT_(f, nm, d, u, dim) MPM_POINT_PERMUTE_(ti, f, dim)
  MPM_POINT_REAL_FIELDS(MPM_POINT_PERMUTE_REAL_)
  MPM_POINT_INT_FIELDS(MPM_POINT_PERMUTE_INT_)
#undef MPM_POINT_PERMUTE_REAL_
#undef MPM_POINT_PERMUTE_INT_
#undef MPM_POINT_PERMUTE_
}
