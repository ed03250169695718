/* body.h: moving rigid bodies, for a mesh of either dimension (docs/model.md,
 * "Rigid bodies and contact").
 *
 * A body is a plane profile (disc, rectangle, polygon) in the plane normal
 * to its axis, turned by an angle about the axis through its centre and, in
 * 3D, extruded along the axis (over a length, or through the mesh). Its
 * material side is outside the profile (a blade, a wheel, an inner
 * cylinder) or inside it (an outer cylinder's wall). Its geometry is a
 * signed distance phi(x), positive in the material, with the unit normal
 * n = grad phi pointing into the material.
 *
 * The solver (solver/bodies.c) corrects the velocity of each node with mass
 * and phi <= h/2 (half a unit: docs/model.md says why) after the grid
 * update, relative to the body's velocity there
 * (mpm_body_contact), sums the change of momentum into the body's force and
 * torque, puts points that end inside the body back on its surface, and
 * moves the body (mpm_body_advance): each degree of freedom (x, y, z, the
 * turn about the axis) prescribed by a table of velocities or free. */
#ifndef MPM_BC_BODY_H
#define MPM_BC_BODY_H

#include <math.h>

#include "core/config.h"
#include "core/state.h"
#include "mesh/mesh.h"

typedef struct mpm_body {
  const mpm_body_config *cfg;  /* the input (not owned; outlives the body) */
  int dim;                     /* 2 or 3 */
  int e[3];                    /* the profile's axes e[0], e[1] and the body's axis e[2] */
  mpm_body_state s;            /* centre, turn, velocity (x, y, z [m/s], omega [rad/s]:
                                  that of the step), the material's force and torque
                                  about the centre over the last step (plane: tq[2]
                                  only), points put back (core/state.h) */
  double ct, sn;               /* cos and sin of s.theta (mpm_body_turned) */
  double reach2;               /* the profile's radius about the centre, squared
                                  (mpm_body_near) */
} mpm_body;

/* The name table of enum mpm_body_shape, _side and _contact: "disc", "box",
 * "polygon"; "outside", "inside"; "noslip", "frictionless", "friction". */
const char *mpm_body_shape_name(int shape);
int mpm_body_shape_from_name(const char *name);
const char *mpm_body_side_name(int side);
int mpm_body_side_from_name(const char *name);
const char *mpm_body_contact_name(int contact);
int mpm_body_contact_from_name(const char *name);

/* The body of cfg in dimension dim at t = 0: centre, turn, and the velocity
 * of its tables at t = 0. */
void mpm_body_init(mpm_body *b, const mpm_body_config *cfg, int dim);

/* The prescribed velocity of degree of freedom k at time t: the table
 * linearly interpolated, its end values outside it. */
double mpm_body_table(const mpm_body_config *cfg, int k, double t);

/* Signed distance of x to the body's surface, > 0 on the material side;
 * n (may be NULL) the unit normal into the material (grad phi). */
double mpm_body_phi(const mpm_body *b, const double x[3], double n[3]);

/* 0 when x is certainly farther than `margin` on the material's side
 * (phi(x) > margin), from the distance to the axis alone: exact for a
 * disc, the profile's bounding circle for material outside a box or
 * polygon (the prism's ends only make phi larger there); 1 otherwise (then
 * mpm_body_phi decides). Cheap, branch-free for a disc: the filter of the
 * point and node passes. */
static inline int mpm_body_near(const mpm_body *b, const double x[3], double margin)
{
  const double X = x[b->e[0]] - b->s.c[b->e[0]], Y = x[b->e[1]] - b->s.c[b->e[1]];
  const double r2 = X * X + Y * Y;
  if (b->cfg->side == MPM_BODY_OUTSIDE) {               /* 1e-9: phi's own rounding */
    const double R = sqrt(b->reach2) * (1.0 + 1e-9) + margin;
    return r2 <= R * R;
  }
  if (b->cfg->shape != MPM_BODY_DISC || (b->dim == 3 && b->cfg->length > 0.0))
    return 1;                                            /* (a drum's caps hold too) */
  const double R = b->cfg->radius * (1.0 - 1e-9) - margin;  /* material inside the disc */
  return R <= 0.0 || r2 >= R * R;
}

/* The body's velocity at x: v + omega a x (x - c), a its axis. */
void mpm_body_velocity_at(const mpm_body *b, const double x[3], double vb[3]);

/* The contact rule on a node velocity v[D] (D = 2 or 3) relative to the
 * body's vb at the node, n the normal into the material: with
 * w = v - vb and w_n = w . n < 0 (approach, or pressing after the forces)
 * noslip sets w = 0, frictionless removes w_n n, friction removes w_n n and
 * shortens the tangential part by mu |w_n| (to zero when shorter). Returns 1
 * if v changed; a separating node (w_n >= 0) is left alone. */
int mpm_body_contact(const mpm_body_config *cfg, int D, const double vb[3], const double n[3],
                     double v[3]);

/* Set the velocity of the prescribed degrees of freedom for a step from t to
 * t + dt (the tables at t + dt/2). */
void mpm_body_prescribe(mpm_body *b, double t, double dt);

/* The end of a step of dt: a free degree of freedom's velocity from the
 * force (contact b->s.f, applied, gravity g on the mass, damping) and the
 * torque about the axis; then the centre and the turn move by dt times the
 * velocity (the new one of a free degree, that of the step otherwise). */
void mpm_body_advance(mpm_body *b, double dt, const double g[3]);

/* Set theta and its cosine and sine. */
void mpm_body_turned(mpm_body *b, double theta);

/* The torque about the axis (the component of tq along it). */
double mpm_body_axial_torque(const mpm_body *b);

/* Storage nodes lo[a] <= i < hi[a] that can lie within a unit of the body,
 * a box of the mesh's stored nodes: the profile's bounding box, one unit
 * wider; the whole mesh for a body whose material is inside. */
void mpm_body_node_box(const mpm_body *b, const mpm_mesh *m, int lo[3], int hi[3]);

/* The body's outline, for pictures (run.xdmf): the profile turned and
 * placed at the centre, as nr rings of nv vertices each, vertex i of ring r
 * at xyz[3 (r nv + i)] (z = 0 in the plane): a disc as an
 * MPM_BODY_OUTLINE_DISC-gon, a box's four corners, a polygon's vertices, in
 * order around the profile. The plane has one ring; 3D two, the profile at
 * both ends of the prism along its axis (+-length/2 about the centre, or the
 * mesh's faces for a body through the mesh). Returns nv; *nr the rings and
 * *caps 1 when the prism's ends are faces of the body (a finite length),
 * 0 when they are open. xyz holds 2 * 3 * MPM_BODY_OUTLINE_MAX values. */
#define MPM_BODY_OUTLINE_DISC 64
#define MPM_BODY_OUTLINE_MAX (MPM_MAX_POLY > MPM_BODY_OUTLINE_DISC ? MPM_MAX_POLY \
                                                                : MPM_BODY_OUTLINE_DISC)
int mpm_body_outline(const mpm_body *b, const mpm_mesh *m, double *xyz, int *nr, int *caps);

/* 1 if the centre is inside the mesh (on a periodic axis: always). */
int mpm_body_in_mesh(const mpm_body *b, const mpm_mesh *m);

#endif
