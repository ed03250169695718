/* shape3.c: the registry of the 3D shape variants (shape3.h) and the delta
 * weights on the trilinear basis, S_ip = N_i(x_p), gradS_ip = grad N_i(x_p)
 * (MODEL.md section 3). The corner rule is in ugimp3.c. */
#include "shape/shape3.h"

#include <string.h>

#include "core/points.h"

const mpm_shape3_type *const mpm_shape3_table[] = {
  &mpm_shape3_delta,
  &mpm_shape3_ugimp,
  &mpm_shape3_cpdi,
  NULL
};

const mpm_shape3_type *mpm_shape3_lookup(const char *name)
{
  if (!name)
    return NULL;
  for (const mpm_shape3_type *const *t = mpm_shape3_table; *t; t++)
    if (strcmp((*t)->name, name) == 0)
      return *t;
  return NULL;
}

static int delta3_eval(const mpm_mesh3 *m, const double x[3], const double r[9], int *node,
                       double *S, double *dSx, double *dSy, double *dSz)
{
  (void)r;  /* no extent: the point is a Dirac mass */
  return mpm_mesh3_basis(m, x, node, S, dSx, dSy, dSz);
}

/* The unit's 8 nodes, all around the point's unit (distinct: a periodic
 * axis has at least two units). */
static void delta3_span(const mpm_mesh3 *m, size_t n, const double *r, int *width, int *reach)
{
  (void)m;
  (void)n;
  (void)r;
  *width = 8;
  *reach = 0;
}

const mpm_shape3_type mpm_shape3_delta = {
  .name = "delta",
  .description = "original MPM: S = N(x_p), gradS = grad N(x_p), trilinear N",
  .eval = delta3_eval,
  .span = delta3_span,
  .at_point = 1,
  .convect = 0,
};

/* The extent half-vectors of point p of a 3D store, r_k = r[3k .. 3k + 2]. */
static void point_extent(const mpm_points *P, size_t p, double r[9])
{
  const double v[9] = {P->r1x[p], P->r1y[p], P->r1z[p], P->r2x[p], P->r2y[p],
                       P->r2z[p], P->r3x[p], P->r3y[p], P->r3z[p]};
  memcpy(r, v, sizeof v);
}

int mpm_shape3_stencil_compute(mpm_shape_stencil *st, const mpm_shape3_type *type,
                               const mpm_mesh3 *m, const mpm_points *pts, double t,
                               mpm_err *err)
{
  const long n = (long)pts->n;
  int w = 1, reach = 0;
  for (long p = 0; p < n; p++) {          /* the widest point: the width of all */
    double r[9];
    int wp, rp;
    point_extent(pts, (size_t)p, r);
    type->span(m, 1, r, &wp, &rp);
    w = wp > w ? wp : w;
    reach = rp > reach ? rp : reach;
  }
  if (mpm_shape_stencil_reserve(st, pts->n, w, 3) != MPM_OK)
    return mpm_err_set(err, MPM_ENOMEM, "stencil for %zu points: out of memory", pts->n);
  st->reach = reach;
  long first = n;
#pragma omp parallel for schedule(static) reduction(min : first)
  for (long p = 0; p < n; p++) {
    const size_t o = (size_t)p * (size_t)w;
    const double x[3] = {pts->x[p], pts->y[p], pts->z[p]};
    double r[9], v;
    point_extent(pts, (size_t)p, r);
    int c = type->eval(m, x, r, st->node + o, st->S + o, st->dSx + o, st->dSy + o, st->dSz + o);
    if (c >= 0 && mpm_mesh_axis_locate(x[2], m->z0, m->lz, m->idz, m->nz, m->periodic_z,
                                       &st->row[p], &v))
      c = -1;
    st->count[p] = c;
    if (c < 0 && p < first)
      first = p;
  }
  if (first < n)
    return mpm_err_set(err, MPM_EOUTSIDE, "point %d left the mesh at (%.6g, %.6g, %.6g) m, "
                       "t = %.6g s (mesh [%g, %g] x [%g, %g] x [%g, %g] m)", pts->id[first],
                       pts->x[first], pts->y[first], pts->z[first], t, m->x0, m->x0 + m->lx,
                       m->y0, m->y0 + m->ly, m->z0, m->z0 + m->lz);
  return MPM_OK;
}
