/* input_body.c: the checks of a rigid body that no single range can state:
 * the keys of its shape, a polygon's vertices (and in 3D its axis, z), its
 * centre inside the mesh, the friction coefficient that belongs to contact
 * "friction", the velocity tables against their times, and the mass and
 * inertia that a free motion needs. The keys of 3D runs are checked with the
 * others (input_check.c). */
#include "io/input_internal.h"

static int body_key(const char *name)
{
  return mpm_io_in_find_key(S_BODY, name);  /* the table is fixed: names used here exist */
}

/* The place of key k of body i. */
static where at_key(const in_ctx *c, const mpm_config *cfg, int i, int k)
{
  where w = {.at = c->at[i][k], .sec = S_BODY, .key = k, .item = i, .title = cfg->body[i].name};
  return w;
}

/* A polygon: 3 ... MPM_MAX_POLY vertices around a region, relative to the
 * centre; in 3D a prism along z only. */
static int check_polygon(in_ctx *c, mpm_config *cfg, int i)
{
  mpm_body_config *b = &cfg->body[i];
  const int kx = body_key("x"), ky = body_key("y");
  double box[4];
  if (mpm_io_in_check_vertices(c, cfg, i, kx, ky, b->px, b->py, box) != MPM_OK)
    return MPM_EINPUT;
  b->nvert = c->nlist[i][kx];
  if (cfg->mesh.nz > 0 && b->axis != 2) {
    where w = mpm_io_in_blame(c, cfg, i, body_key("axis"), body_key("shape"));
    return mpm_io_in_fail_key(c, &w, "shape = \"polygon\" with axis = \"%s\" (allowed: axis "
                              "\"z\" for a polygon; a disc or a box along any axis)",
                              mpm_io_in_name_at(NK_FILL_AXIS, b->axis));
  }
  return MPM_OK;
}

/* The centre, the reference point of the profile and of the rotation,
 * inside the mesh: cx, cy, and in 3D cz. */
static int check_centre(in_ctx *c, const mpm_config *cfg, int i)
{
  const mpm_body_config *b = &cfg->body[i];
  const char *const name[3] = {"cx", "cy", "cz"};
  const double v[3] = {b->cx, b->cy, b->cz};
  for (int a = 0; a < (cfg->mesh.nz > 0 ? 3 : 2); a++) {
    const mesh_axis ax = mpm_io_in_mesh_axis(cfg, a);
    const double m1 = ax.o + ax.n * ax.d, tol = GEOM_TOL * ax.d;
    if (v[a] >= ax.o - tol && v[a] <= m1 + tol)
      continue;
    where w = at_key(c, cfg, i, body_key(name[a]));
    return mpm_io_in_fail_key(c, &w, "%s = %s lies outside the mesh (allowed: %s ... %s m)",
                              name[a], mpm_io_in_num(v[a]).s, mpm_io_in_approx(ax.o).s,
                              mpm_io_in_approx(m1).s);
  }
  return MPM_OK;
}

/* The Coulomb coefficient is that of contact "friction", and it needs one. */
static int check_friction(in_ctx *c, const mpm_config *cfg, int i)
{
  const mpm_body_config *b = &cfg->body[i];
  where w = at_key(c, cfg, i, body_key("friction"));
  if (b->contact == MPM_CONTACT_FRICTION && !(b->friction > 0.0))
    return mpm_io_in_fail_key(c, &w, "contact = \"friction\" with friction = %s (allowed: "
                              "friction > 0 with contact = \"friction\")",
                              mpm_io_in_num(b->friction).s);
  if (b->contact != MPM_CONTACT_FRICTION && b->friction > 0.0)
    return mpm_io_in_fail_key(c, &w, "friction = %s with contact = \"%s\": the coefficient "
                              "belongs to contact = \"friction\" (allowed: contact = "
                              "\"friction\", or friction = 0)", mpm_io_in_num(b->friction).s,
                              mpm_io_in_name_at(NK_BODY_CONTACT, b->contact));
  return MPM_OK;
}

/* The velocity keys of the degrees of freedom, and their free keys. */
static const char *const velocity_key[MPM_BODY_NDOF] = {"vx", "vy", "vz", "omega"};
static const char *const free_key[MPM_BODY_NDOF] = {"free_x", "free_y", "free_z",
                                                    "free_rotation"};

/* Each velocity table: one value (constant; a velocity not given is the one
 * value 0) or one for each time of t. */
static int check_tables(in_ctx *c, mpm_config *cfg, int i)
{
  mpm_body_config *b = &cfg->body[i];
  const int kt = body_key("t");
  b->ntable = c->nlist[i][kt];
  for (int d = 0; d < MPM_BODY_NDOF; d++) {
    const int k = body_key(velocity_key[d]);
    const int n = mpm_io_in_is_set(c, k, i) ? c->nlist[i][k] : 1;
    if (n != 1 && !(n > 1 && n == b->ntable)) {
      where w = mpm_io_in_blame(c, cfg, i, k, kt);
      return mpm_io_in_fail_key(c, &w, "%s has %d values, t has %d (allowed: 1 value, or as "
                                "many as t)", velocity_key[d], n, b->ntable);
    }
    b->nval[d] = n;
  }
  return MPM_OK;
}

/* A free translation needs a mass, a free rotation an inertia. */
static int check_free(in_ctx *c, const mpm_config *cfg, int i)
{
  const mpm_body_config *b = &cfg->body[i];
  for (int d = 0; d < MPM_BODY_NDOF; d++) {
    const int rotation = d == MPM_BODY_OMEGA;
    const double m = rotation ? b->inertia : b->mass;
    if (!b->free[d] || m > 0.0)
      continue;
    where w = at_key(c, cfg, i, body_key(free_key[d]));
    return mpm_io_in_fail_key(c, &w, "free %s without %s, %s = %s (allowed: %s > 0 with %s = "
                              "true, or %s = false)", rotation ? "rotation" : "axis",
                              rotation ? "an inertia" : "a mass", rotation ? "inertia" : "mass",
                              mpm_io_in_num(m).s, rotation ? "inertia" : "mass", free_key[d],
                              free_key[d]);
  }
  return MPM_OK;
}

/* Body i: the keys of its shape, its profile and centre, its contact and
 * its motion. */
int mpm_io_in_check_body(in_ctx *c, mpm_config *cfg, int i)
{
  if (mpm_io_in_check_form_keys(c, cfg, T_BODY, i) != MPM_OK)
    return MPM_EINPUT;
  if (cfg->body[i].shape == MPM_BODY_POLYGON && check_polygon(c, cfg, i) != MPM_OK)
    return MPM_EINPUT;
  if (check_centre(c, cfg, i) != MPM_OK || check_friction(c, cfg, i) != MPM_OK ||
      check_tables(c, cfg, i) != MPM_OK)
    return MPM_EINPUT;
  return check_free(c, cfg, i);
}
