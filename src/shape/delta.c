/* delta.c: original MPM weights, S_ip = N_i(x_p), gradS_ip = grad N_i(x_p)
 * (MODEL.md section 3), on either mesh. The element basis comes from the
 * mesh; its nodes are distinct, but on a periodic axis of one unit, where
 * the unit's two node columns (or rows) are one node: it is listed twice,
 * and point-to-grid adds both. */
#include "shape/shape.h"

static int delta_eval(const mpm_mesh *m, const double x[3], const double *r, int *node,
                      double *S, double *const dS[3])
{
  (void)r;  /* no extent: the point is a Dirac mass */
  return mpm_mesh_basis(m, x, node, S, dS);
}

/* The element's nodes: 4 (Q4), 3 (T3) or 8 (a box), all of the point's
 * unit. */
static void delta_span(const mpm_mesh *m, const mpm_points *pts, int *width, int *reach)
{
  (void)pts;
  *width = m->dim == 3 ? 8 : m->topology == MPM_TOPO_Q4 ? 4 : 3;
  *reach = 0;
}

const mpm_shape_type mpm_shape_delta = {
  .name = "delta",
  .description = "original MPM: S = N(x_p), gradS = grad N(x_p)",
  .eval = delta_eval,
  .span = delta_span,
  .at_point = 1,
  .convect = 0,
};
