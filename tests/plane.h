/* plane.h: the mesh and shape calls of the plane tests in plane form, on the
 * one mesh of either dimension (mesh.h, shape.h): positions (x, y) instead
 * of x[3] = (x, y, 0), units and nodes (i, j) instead of c[3] = (i, j, 0),
 * gradients as two arrays. Each is the library call with z = 0, nothing
 * more. */
#ifndef TESTS_PLANE_H
#define TESTS_PLANE_H

#include "bc/bc.h"
#include "mesh/mesh.h"
#include "shape/shape.h"

static inline int plane_node(const mpm_mesh *m, int i, int j)
{
  return mpm_mesh_node(m, i, j, 0);
}

static inline void plane_node_pos(const mpm_mesh *m, int i, int j, double *x, double *y)
{
  double p[3];
  mpm_mesh_node_pos(m, i, j, 0, p);
  *x = p[0];
  *y = p[1];
}

static inline int plane_unit(const mpm_mesh *m, double x, double y, int *i, int *j)
{
  const double p[3] = {x, y, 0.0};
  int c[3] = {0, 0, 0};
  const int rc = mpm_mesh_unit(m, p, c);
  *i = c[0];
  *j = c[1];
  return rc;
}

static inline int plane_locate(const mpm_mesh *m, double x, double y, int *i, int *j, double *u,
                               double *v)
{
  const double p[3] = {x, y, 0.0};
  int c[3] = {0, 0, 0};
  double l[3] = {0.0, 0.0, 0.0};
  const int rc = mpm_mesh_locate(m, p, c, l);
  *i = c[0];
  *j = c[1];
  *u = l[0];
  *v = l[1];
  return rc;
}

static inline void plane_wrap(const mpm_mesh *m, double *x, double *y)
{
  double p[3] = {*x, *y, 0.0};
  mpm_mesh_wrap(m, p);
  *x = p[0];
  *y = p[1];
}

static inline int plane_basis(const mpm_mesh *m, double x, double y, int *node, double *N,
                              double *dNx, double *dNy)
{
  const double p[3] = {x, y, 0.0};
  double *const dN[3] = {dNx, dNy, NULL};
  return mpm_mesh_basis(m, p, node, N, dN);
}

static inline void plane_unit_corners(const mpm_mesh *m, int i, int j, int node[4])
{
  const int c[3] = {i, j, 0};
  mpm_mesh_unit_corners(m, c, node);
}

static inline int plane_eval(const mpm_shape_type *t, const mpm_mesh *m, double x, double y,
                             const double r[4], int *node, double *S, double *dSx, double *dSy)
{
  const double p[3] = {x, y, 0.0};
  double *const dS[3] = {dSx, dSy, NULL};
  return t->eval(m, p, r, node, S, dS);
}

/* An interval [from, to] of edge e (MPM_FACE_XLO .. MPM_FACE_YHI) as the
 * outlet: the box of one axis on that face. */
static inline int plane_set_outlet(mpm_bc *bc, const mpm_mesh *m, int e, double from, double to,
                                   int closed, int held_ends, mpm_err *err)
{
  const double lo[2] = {from, 0.0}, hi[2] = {to, 0.0};
  return mpm_bc_set_outlet(bc, m, e, MPM_BC_OUTLET_BOX, lo, hi, closed, held_ends, err);
}

/* The open unit faces lo .. hi-1 along the outlet's edge; returns the edge. */
static inline int plane_outlet_faces(const mpm_bc *bc, const mpm_mesh *m, int *lo, int *hi)
{
  int l[3], h[3], ax[2] = {0, 0};
  const int f = mpm_bc_outlet_faces(bc, m, l, h);
  if (f >= 0)
    mpm_bc_face_axes(m->dim, f, ax);
  *lo = f >= 0 ? l[ax[0]] : 0;
  *hi = f >= 0 ? h[ax[0]] : 0;
  return f;
}

static inline int plane_left_through(const mpm_bc *bc, const mpm_mesh *m, double x, double y)
{
  const double p[3] = {x, y, 0.0};
  return mpm_bc_left_through_outlet(bc, m, p);
}

/* What the step does with a point beyond the mesh (kernels.inc's
 * bookkeeping): nothing when it left through the open outlet, else each
 * axis clamped onto a wall with its velocity into it limited to the grid's
 * (gvx, gvy). */
static inline void plane_clamp(const mpm_bc *bc, const mpm_mesh *m, double *x, double *y,
                               double *vx, double *vy, double gvx, double gvy)
{
  if (plane_left_through(bc, m, *x, *y))
    return;
  mpm_bc_clamp_axis(x, vx, gvx, m->x0, m->x0 + m->lx, mpm_bc_is_wall(bc->face[MPM_FACE_XLO]),
                    mpm_bc_is_wall(bc->face[MPM_FACE_XHI]));
  mpm_bc_clamp_axis(y, vy, gvy, m->y0, m->y0 + m->ly, mpm_bc_is_wall(bc->face[MPM_FACE_YLO]),
                    mpm_bc_is_wall(bc->face[MPM_FACE_YHI]));
}

#endif
