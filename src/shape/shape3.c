/* shape3.c: the registry of the 3D shape variants (shape3.h) and the delta
 * weights on the trilinear basis, S_ip = N_i(x_p), gradS_ip = grad N_i(x_p)
 * (MODEL.md section 3). The corner rule is in ugimp3.c. */
#include "shape/shape3.h"

#include <string.h>

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
