/* delta.c: original MPM weights, S_ip = N_i(x_p), gradS_ip = grad N_i(x_p)
 * (MODEL.md section 3). The element basis comes from the mesh; its nodes are
 * distinct (periodic meshes have at least two units per direction). */
#include "shape/shape.h"

static int delta_eval(const mpm_mesh *m, double x, double y, const double r[4],
                      int *node, double *S, double *dSx, double *dSy)
{
  (void)r;  /* no extent: the point is a Dirac mass */
  return mpm_mesh_basis(m, x, y, node, S, dSx, dSy);
}

const mpm_shape_type mpm_shape_delta = {
  "delta",
  "original MPM: S = N(x_p), gradS = grad N(x_p)",
  delta_eval
};
