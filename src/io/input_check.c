/* input_check.c: the relations between keys that no single range can state
 * (mesh size, time, gravity given one way, material parameters in order,
 * periodic edges in pairs, outlet, wall, region, the keys of 3D runs), the
 * defaults that follow other keys (t_seed, stop.t_min, gravity from an
 * angle), and the model's own parameter check; the items of the titled
 * sections are checked by input_fill.c and input_body.c. A relation between
 * two keys is reported at the one set last (input_shared.c). */
#include <math.h>
#include <string.h>

#include "bc/bc.h"
#include "io/input_internal.h"
#include "material/density.h"
#include "material/material.h"
#include "nonlocal/field.h"
#include "shape/shape.h"

#define MAX_NODES 1e8  /* (nx + 1)(ny + 1) */

static int key_index(int sec, const char *name)
{
  return mpm_io_in_find_key(sec, name);  /* the table is fixed: names used here exist */
}

static int check_required(in_ctx *c)
{
  for (int k = 0; k < NKEYS; k++) {
    if (mpm_io_in_titled_of(mpm_io_in_keys[k].sec) >= 0 ||
        !(mpm_io_in_keys[k].flags & KF_REQUIRED) || mpm_io_in_is_set(c, k, -1))
      continue;
    where w = {.sec = mpm_io_in_keys[k].sec, .key = k, .item = -1};
    return mpm_io_in_fail_key(c, &w, "required, not set (allowed: %s)",
                              mpm_io_in_allowed_text(&mpm_io_in_keys[k]).s);
  }
  return MPM_OK;
}

/* The units a periodic axis needs under APIC, which finds a stencil node's
 * position from its stored index: the axis must hold the stencil's nodes
 * without two being one (2 for weights that are the element basis at the
 * point, 4 for extents up to half a unit: mpm_sim_in_node_offset). */
static int apic_axis_need(const mpm_config *cfg)
{
  const mpm_shape_type *shape = mpm_shape_lookup(cfg->mesh.shape);
  return shape && shape->at_point ? 2 : 4;   /* the 3D shapes share the names and rules */
}

/* The axis (0: x, 1: y, 2: z) too short for APIC, or -1. */
static int apic_short_axis(const mpm_config *cfg)
{
  const int need = apic_axis_need(cfg);
  if (cfg->bc.left == MPM_BC_PERIODIC && cfg->mesh.nx < need)
    return 0;
  if (cfg->bc.bottom == MPM_BC_PERIODIC && cfg->mesh.ny < need)
    return 1;
  if (cfg->mesh.nz > 0 && cfg->bc.front == MPM_BC_PERIODIC && cfg->mesh.nz < need)
    return 2;
  return -1;
}

/* The scheme's defaults follow the run (docs/input-reference.md, "The
 * scheme"): the options that give clean fields wherever they exist, the
 * paper's rules where they do not. A key the input sets is kept as set. */
static void resolve_scheme(in_ctx *c, mpm_config *cfg)
{
  const int plane = cfg->mesh.nz == 0, q4 = strcmp(cfg->mesh.topology, "q4") == 0;
  if (!mpm_io_in_is_set(c, key_index(S_MESH, "dilatation"), -1) && plane && !q4)
    cfg->mesh.dilatation = MPM_DILATATION_UNIT;  /* the Q1/P0 element is the units' */
  /* no affine transfer on a periodic axis too short for it; and a FLIP
   * share given alone asks for the blend */
  if (!mpm_io_in_is_set(c, key_index(S_TIME, "transfer"), -1) &&
      (apic_short_axis(cfg) >= 0 || mpm_io_in_is_set(c, key_index(S_TIME, "flip"), -1)))
    cfg->time.transfer = MPM_TRANSFER_FLIP;
  /* delta weights keep a lone point's affine velocity whole: under a
   * per-unit rule a stress-free point then swells and is thrown out of the
   * mesh at cfl 0.5 (docs/input-reference.md, time.cfl) */
  const mpm_shape_type *shape = mpm_shape_lookup(cfg->mesh.shape);
  if (!mpm_io_in_is_set(c, key_index(S_TIME, "cfl"), -1) && shape && shape->at_point &&
      cfg->time.transfer == MPM_TRANSFER_APIC &&
      (cfg->mesh.dilatation != MPM_DILATATION_POINT ||
       cfg->material.state_density == MPM_DENSITY_UNIT))
    cfg->time.cfl = 0.25;
}

static int check_mesh(in_ctx *c, const mpm_config *cfg)
{
  double nodes = (cfg->mesh.nx + 1.0) * (cfg->mesh.ny + 1.0);
  if (nodes > MAX_NODES) {
    where w = mpm_io_in_blame(c, cfg, -1, key_index(S_MESH, "nx"), key_index(S_MESH, "ny"));
    return mpm_io_in_fail_key(c, &w, "%d x %d units make %s nodes (allowed: (nx+1)(ny+1) <= %s)",
                              cfg->mesh.nx, cfg->mesh.ny, mpm_io_in_num(nodes).s,
                              mpm_io_in_num(MAX_NODES).s);
  }
  const int px = cfg->bc.left == MPM_BC_PERIODIC, py = cfg->bc.bottom == MPM_BC_PERIODIC;
  /* a plane periodic axis may be one unit (one node column or row); the 3D
   * box keeps two */
  if (cfg->mesh.nz > 0) {
    const int per[3] = {px, py, cfg->bc.front == MPM_BC_PERIODIC};
    const int n[3] = {cfg->mesh.nx, cfg->mesh.ny, cfg->mesh.nz};
    const char *const name[3] = {"nx", "ny", "nz"};
    for (int a = 0; a < 3; a++)
      if (per[a] && n[a] < 2) {
        const int k = key_index(S_MESH, name[a]);
        where w = mpm_io_in_blame(c, cfg, -1, k, k);
        return mpm_io_in_fail_key(c, &w, "%s = 1 on a periodic axis of a 3D run (allowed: at "
                                  "least 2; a plane run may have 1)", name[a]);
      }
  }
  /* the Q1/P0 element integral of a filled unit is written for the
   * (bi/tri)linear units */
  if (cfg->mesh.dilatation == MPM_DILATATION_ELEMENT && cfg->mesh.nz == 0 &&
      strcmp(cfg->mesh.topology, "q4") != 0) {
    const int k = key_index(S_MESH, "dilatation");
    where w = mpm_io_in_blame(c, cfg, -1, k, key_index(S_MESH, "topology"));
    return mpm_io_in_fail_key(c, &w, "dilatation = \"element\" on triangles (allowed: topology "
                              "\"q4\" or a 3D run; \"unit\" or \"point\" otherwise)");
  }
  const int axis = apic_short_axis(cfg);
  if (cfg->time.transfer == MPM_TRANSFER_APIC && axis >= 0) {
    const char *const nname[3] = {"nx", "ny", "nz"};
    const int nunits[3] = {cfg->mesh.nx, cfg->mesh.ny, cfg->mesh.nz};
    where w = mpm_io_in_blame(c, cfg, -1, key_index(S_TIME, "transfer"),
                              key_index(S_MESH, nname[axis]));
    return mpm_io_in_fail_key(c, &w, "transfer = \"apic\" with shape = \"%s\" on a periodic "
                              "axis of %d units (allowed: at least %d)", cfg->mesh.shape,
                              nunits[axis], apic_axis_need(cfg));
  }
  double x1 = cfg->mesh.x0 + cfg->mesh.nx * cfg->mesh.dx, tol = GEOM_TOL * cfg->mesh.dx;
  double m = cfg->mesh.mirror_x;
  if (strcmp(cfg->mesh.diagonal, "mirror") == 0 && (m < cfg->mesh.x0 - tol || m > x1 + tol)) {
    where w = mpm_io_in_blame(c, cfg, -1, key_index(S_MESH, "mirror_x"),
                              key_index(S_MESH, "diagonal"));
    return mpm_io_in_fail_key(c, &w, "mirror_x = %s lies outside the mesh (allowed: %s ... %s m)",
                              mpm_io_in_num(m).s, mpm_io_in_approx(cfg->mesh.x0).s,
                              mpm_io_in_approx(x1).s);
  }
  return MPM_OK;
}

static int check_time(in_ctx *c, const mpm_config *cfg)
{
  if (cfg->time.frame_dt > cfg->time.t_end) {
    where w = mpm_io_in_blame(c, cfg, -1, key_index(S_TIME, "frame_dt"),
                              key_index(S_TIME, "t_end"));
    return mpm_io_in_fail_key(c, &w, "frame_dt = %s > t_end = %s (allowed: frame_dt <= t_end)",
                              mpm_io_in_num(cfg->time.frame_dt).s,
                              mpm_io_in_num(cfg->time.t_end).s);
  }
  return MPM_OK;
}

/* Gravity is either the vector (gx, gy) or an incline angle with a magnitude
 * g: gx = g sin(angle), gy = -g cos(angle), so material flows towards +x on a
 * base along x. The two ways cannot be mixed. */
static int check_gravity(in_ctx *c, mpm_config *cfg)
{
  const int ka = key_index(S_GRAVITY, "angle"), kg = key_index(S_GRAVITY, "g");
  const int kx = key_index(S_GRAVITY, "gx"), ky = key_index(S_GRAVITY, "gy");
  const int polar = mpm_io_in_is_set(c, ka, -1) ? ka : mpm_io_in_is_set(c, kg, -1) ? kg : -1;
  const int cart = mpm_io_in_is_set(c, kx, -1) ? kx : mpm_io_in_is_set(c, ky, -1) ? ky : -1;
  cfg->gravity.use_angle = polar >= 0;
  if (polar < 0)
    return MPM_OK;
  if (cart >= 0) {
    where w = mpm_io_in_blame(c, cfg, -1, polar, cart);
    return mpm_io_in_fail_key(c, &w,
                              "gravity given both as gx, gy and as angle, g "
                              "(allowed: one of the two)");
  }
  const double a = cfg->gravity.angle * (3.14159265358979323846 / 180.0);  /* deg -> rad */
  cfg->gravity.gx = cfg->gravity.g * sin(a);
  cfg->gravity.gy = -cfg->gravity.g * cos(a);
  return MPM_OK;
}

/* The kinetic-energy stop test starts after the gravity ramp unless told
 * otherwise: material loaded from rest has no kinetic energy at first. */
static void resolve_stop(in_ctx *c, mpm_config *cfg)
{
  if (!mpm_io_in_is_set(c, key_index(S_STOP, "t_min"), -1))
    cfg->stop.t_min = cfg->gravity.t_ramp;
}

static int check_material(in_ctx *c, mpm_config *cfg)
{
  for (int k = 0; k < NKEYS; k++)  /* NGF seeding time: 10 t0 unless given ([DK-silo] 6) */
    if ((mpm_io_in_keys[k].flags & KF_T0X10) && !mpm_io_in_is_set(c, k, -1))
      *(double *)(void *)((char *)cfg + mpm_io_in_keys[k].off) = 10.0 * cfg->material.t0;
  if (cfg->material.rho_c > cfg->material.rho_s) {
    where w = mpm_io_in_blame(c, cfg, -1, key_index(S_MATERIAL, "rho_c"),
                              key_index(S_MATERIAL, "rho_s"));
    return mpm_io_in_fail_key(c, &w, "rho_c = %s > rho_s = %s (allowed: rho_c <= rho_s)",
                              mpm_io_in_num(cfg->material.rho_c).s,
                              mpm_io_in_num(cfg->material.rho_s).s);
  }
  const int kn = key_index(S_MATERIAL, "n_sub"), kd = key_index(S_MATERIAL, "dt_sub");
  if (cfg->material.n_sub > 1 && cfg->material.dt_sub > 0.0) {  /* two ways to say it */
    where w = mpm_io_in_blame(c, cfg, -1, kd, kn);
    return mpm_io_in_fail_key(c, &w,
                              "n_sub = %d with dt_sub = %s s (allowed: n_sub = 1 or dt_sub = 0)",
                              cfg->material.n_sub, mpm_io_in_num(cfg->material.dt_sub).s);
  }
  if (cfg->material.mu_s >= cfg->material.mu_2) {
    where w = mpm_io_in_blame(c, cfg, -1, key_index(S_MATERIAL, "mu_s"),
                              key_index(S_MATERIAL, "mu_2"));
    return mpm_io_in_fail_key(c, &w, "mu_s = %s >= mu_2 = %s (allowed: mu_s < mu_2)",
                              mpm_io_in_num(cfg->material.mu_s).s,
                              mpm_io_in_num(cfg->material.mu_2).s);
  }
  /* The steady solve is [D-thesis]'s equation, whose local law is the linear
   * mu = mu_s + b I of the hs21 form; the dk form has no steady fluidity at
   * mu >= mu_2. */
  if (cfg->material.diffusion == MPM_DIFFUSION_STEADY && cfg->material.form != MPM_NGF_HS21) {
    where w = mpm_io_in_blame(c, cfg, -1, key_index(S_MATERIAL, "form"),
                              key_index(S_MATERIAL, "diffusion"));
    return mpm_io_in_fail_key(c, &w,
                              "diffusion = \"steady\" with form = \"%s\": the steady equation "
                              "of [D-thesis] has the linear local law (allowed: form = \"hs21\", "
                              "or diffusion = \"explicit\" or \"implicit\")",
                              mpm_material_ngf_form_name(cfg->material.form));
  }
  return MPM_OK;
}

static int check_periodic_pair(in_ctx *c, const mpm_config *cfg, const char *a, const char *b,
                               int ka, int kb)
{
  int pa = ka == MPM_BC_PERIODIC, pb = kb == MPM_BC_PERIODIC;
  if (pa == pb)
    return MPM_OK;
  where w = mpm_io_in_blame(c, cfg, -1, key_index(S_BOUNDARY, a), key_index(S_BOUNDARY, b));
  return mpm_io_in_fail_key(
      c, &w, "%s = \"%s\" but %s = \"%s\" (allowed: %s and %s both \"periodic\" or neither)", a,
      mpm_bc_kind_name(ka), b, mpm_bc_kind_name(kb), a, b);
}

static int check_boundary(in_ctx *c, const mpm_config *cfg)
{
  if (check_periodic_pair(c, cfg, "left", "right", cfg->bc.left, cfg->bc.right) != MPM_OK)
    return MPM_EINPUT;
  return check_periodic_pair(c, cfg, "bottom", "top", cfg->bc.bottom, cfg->bc.top);
}

/* The model's own parameter check; its message names the key. */
static int check_model(in_ctx *c, const mpm_config *cfg)
{
  const mpm_material_type *t = mpm_material_lookup(cfg->material.model);
  if (!t || !t->check)
    return MPM_OK;
  mpm_material_params par;
  mpm_material_params_from_config(&par, cfg);
  mpm_err e = {0};
  if (t->check(&par, &e) == MPM_OK)
    return MPM_OK;
  int k = key_index(S_MATERIAL, "model");
  const char *named = strstr(e.msg, "key 'material.");
  if (named) {
    char key[MPM_NAME_MAX] = {0};
    const char *q = named + strlen("key 'material.");
    size_t n = strcspn(q, "'");
    memcpy(key, q, n < sizeof key ? n : sizeof key - 1);
    if (mpm_io_in_find_key(S_MATERIAL, key) >= 0)
      k = mpm_io_in_find_key(S_MATERIAL, key);
  }
  where w = {.at = c->at[0][k], .sec = S_MATERIAL, .key = k, .item = -1};
  if (named)
    return mpm_io_in_fail_at(c, &w, "%s", e.msg);
  return mpm_io_in_fail_key(c, &w, "model \"%s\": %s", mpm_io_in_show(cfg->material.model).s,
                            e.msg);
}

/* One extent of an outlet, lo ... hi (keys klo, khi), inside the mesh along
 * axis a (0 x, 1 y, 2 z) of the face of edge e. */
static int check_outlet_span(in_ctx *c, const mpm_config *cfg, int e, int a, int klo, int khi,
                             double lo, double hi)
{
  const mesh_axis ax = mpm_io_in_mesh_axis(cfg, a);
  const double m0 = ax.o, m1 = m0 + ax.n * ax.d, tol = GEOM_TOL * ax.d;
  if (!(hi > lo)) {
    where w = mpm_io_in_blame(c, cfg, -1, khi, klo);
    return mpm_io_in_fail_key(c, &w, "%s = %s <= %s = %s (allowed: %s > %s)",
                              mpm_io_in_keys[khi].name, mpm_io_in_num(hi).s,
                              mpm_io_in_keys[klo].name, mpm_io_in_num(lo).s,
                              mpm_io_in_keys[khi].name, mpm_io_in_keys[klo].name);
  }
  if (lo < m0 - tol || hi > m1 + tol) {
    where w = mpm_io_in_blame(c, cfg, -1, khi, klo);
    return mpm_io_in_fail_key(
        c, &w, "the outlet spans %c %s ... %s, outside the %s %s (allowed: %s ... %s m)",
        "xyz"[a], mpm_io_in_approx(lo).s, mpm_io_in_approx(hi).s, mpm_io_in_name_at(NK_EDGE, e),
        cfg->mesh.nz > 0 ? "face" : "edge", mpm_io_in_approx(m0).s, mpm_io_in_approx(m1).s);
  }
  return MPM_OK;
}

/* Held ends (outlet.ends = "fixed"): along axis a of the outlet's face (0
 * x, 1 y, 2 z), the first node past `from` must lie before `to`, unless an
 * end lies on a symmetry boundary (its node is then freed: bc.h). */
static int check_held_ends(in_ctx *c, const mpm_config *cfg, int a, double from, double to,
                           int kt)
{
  const mesh_axis ax = mpm_io_in_mesh_axis(cfg, a);
  const int lo_kind[3] = {cfg->bc.left, cfg->bc.bottom, cfg->bc.front};
  const int hi_kind[3] = {cfg->bc.right, cfg->bc.top, cfg->bc.back};
  const double tol = GEOM_TOL * ax.d;
  if ((lo_kind[a] == MPM_BC_SYMMETRY && from <= ax.o + tol) ||
      (hi_kind[a] == MPM_BC_SYMMETRY && to >= ax.o + ax.n * ax.d - tol))
    return MPM_OK;
  const double first = ax.o + (floor((from - ax.o) / ax.d + GEOM_TOL) + 1.0) * ax.d;
  if (first < to - tol)
    return MPM_OK;
  where w = mpm_io_in_blame(c, cfg, -1, key_index(S_OUTLET, "ends"), kt);
  return mpm_io_in_fail_key(c, &w, "\"fixed\" leaves no node free between the held ends "
                            "at %s and %s m (allowed: a node strictly between from and to, "
                            "or ends = \"free\")", mpm_io_in_approx(from).s,
                            mpm_io_in_approx(to).s);
}

/* Outlet: an extent on a non-periodic edge (a rectangle or disc on a face
 * in 3D), inside it; closed by a wall. */
static int check_outlet(in_ctx *c, const mpm_config *cfg)
{
  const int e = cfg->outlet.edge;
  if (e == MPM_OUTLET_NONE)
    return MPM_OK;
  const int kf = key_index(S_OUTLET, "from"), kt = key_index(S_OUTLET, "to");
  const int ke = key_index(S_OUTLET, "edge"), kc = key_index(S_OUTLET, "closed");
  const int dim3 = cfg->mesh.nz > 0;
  if (cfg->outlet.closed != MPM_BC_NOSLIP && cfg->outlet.closed != MPM_BC_FRICTIONLESS) {
    where w = mpm_io_in_blame(c, cfg, -1, kc, kc);
    return mpm_io_in_fail_key(c, &w, "\"%s\" (allowed: \"noslip\", \"frictionless\")",
                              mpm_bc_kind_name(cfg->outlet.closed));
  }
  if (!dim3 && (e == MPM_OUTLET_FRONT || e == MPM_OUTLET_BACK)) {
    where w = mpm_io_in_blame(c, cfg, -1, ke, ke);
    return mpm_io_in_fail_key(c, &w, "\"%s\" is a face of 3D runs (allowed in a plane run: "
                              "\"none\", \"left\", \"right\", \"bottom\", \"top\")",
                              mpm_io_in_name_at(NK_EDGE, e));
  }
  const int kinds[] = {0, cfg->bc.left, cfg->bc.right, cfg->bc.bottom, cfg->bc.top,
                       cfg->bc.front, cfg->bc.back};
  if (kinds[e] == MPM_BC_PERIODIC) {
    where w = mpm_io_in_blame(c, cfg, -1, ke, ke);
    return mpm_io_in_fail_key(c, &w, "\"%s\" is periodic (allowed: a non-periodic %s)",
                              mpm_io_in_name_at(NK_EDGE, e), dim3 ? "face" : "edge");
  }
  /* the face's axes: y (z) on left and right, x (z) on bottom and top, x, y
   * on front and back */
  const int a0 = e == MPM_OUTLET_LEFT || e == MPM_OUTLET_RIGHT ? 1 : 0;
  const int a1 = e == MPM_OUTLET_FRONT || e == MPM_OUTLET_BACK ? 1 : 2;
  if (check_outlet_span(c, cfg, e, a0, kf, kt, cfg->outlet.from, cfg->outlet.to) != MPM_OK)
    return MPM_EINPUT;
  if (cfg->outlet.ends == MPM_OUTLET_ENDS_FIXED &&
      check_held_ends(c, cfg, a0, cfg->outlet.from, cfg->outlet.to, kt) != MPM_OK)
    return MPM_EINPUT;
  if (!dim3)
    return MPM_OK;
  const int kf2 = key_index(S_OUTLET, "from2"), kt2 = key_index(S_OUTLET, "to2");
  if (check_outlet_span(c, cfg, e, a1, kf2, kt2, cfg->outlet.from2, cfg->outlet.to2) != MPM_OK)
    return MPM_EINPUT;
  if (cfg->outlet.ends == MPM_OUTLET_ENDS_FIXED &&
      check_held_ends(c, cfg, a1, cfg->outlet.from2, cfg->outlet.to2, kt2) != MPM_OK)
    return MPM_EINPUT;
  const double w0 = cfg->outlet.to - cfg->outlet.from, w1 = cfg->outlet.to2 - cfg->outlet.from2;
  if (cfg->outlet.shape == MPM_OUTLET_DISC && fabs(w0 - w1) > 1e-9 * (w0 > w1 ? w0 : w1)) {
    where w = mpm_io_in_blame(c, cfg, -1, key_index(S_OUTLET, "shape"), kt2);
    return mpm_io_in_fail_key(c, &w, "shape = \"disc\" on %s x %s m (allowed: a square, "
                              "to - from = to2 - from2: the disc is the inscribed one)",
                              mpm_io_in_approx(w0).s, mpm_io_in_approx(w1).s);
  }
  if (cfg->outlet.ends == MPM_OUTLET_ENDS_FIXED && cfg->outlet.shape == MPM_OUTLET_DISC) {
    /* a node strictly inside the disc: the one nearest its centre */
    const mesh_axis x0 = mpm_io_in_mesh_axis(cfg, a0), x1 = mpm_io_in_mesh_axis(cfg, a1);
    const double c0 = 0.5 * (cfg->outlet.from + cfg->outlet.to);
    const double c1 = 0.5 * (cfg->outlet.from2 + cfg->outlet.to2);
    const double r = 0.5 * (cfg->outlet.to - cfg->outlet.from);
    const double d0 = x0.o + round((c0 - x0.o) / x0.d) * x0.d - c0;
    const double d1 = x1.o + round((c1 - x1.o) / x1.d) * x1.d - c1;
    if (!(hypot(d0, d1) < r - GEOM_TOL * fmin(x0.d, x1.d))) {
      where w = mpm_io_in_blame(c, cfg, -1, key_index(S_OUTLET, "ends"), kt2);
      return mpm_io_in_fail_key(c, &w, "\"fixed\" leaves no node free inside the disc of "
                                "radius %s m (allowed: a node strictly inside it, or ends = "
                                "\"free\")", mpm_io_in_approx(r).s);
    }
  }
  return MPM_OK;
}

/* Wall polygon: as many x as y values, none or 3 ... MPM_MAX_POLY; a wall kind. */
static int check_wall(in_ctx *c, mpm_config *cfg)
{
  const int kx = key_index(S_WALL, "x"), ky = key_index(S_WALL, "y");
  const int nx = c->nlist[0][kx], ny = c->nlist[0][ky];
  where w = mpm_io_in_blame(c, cfg, -1, ky, kx);
  if (nx != ny)
    return mpm_io_in_fail_key(
        c, &w, "x has %d values, y has %d (allowed: as many x values as y values)", nx, ny);
  if (nx > 0 && nx < 3)
    return mpm_io_in_fail_key(c, &w, "%d vertices (allowed: none, or 3 ... %d vertices)", nx,
                              MPM_MAX_POLY);
  cfg->wall.nvert = nx;
  const int kk = key_index(S_WALL, "kind");
  if (cfg->wall.kind != MPM_BC_NOSLIP && cfg->wall.kind != MPM_BC_FRICTIONLESS) {
    where wk = mpm_io_in_blame(c, cfg, -1, kk, kk);
    return mpm_io_in_fail_key(c, &wk, "\"%s\" (allowed: \"noslip\", \"frictionless\")",
                              mpm_bc_kind_name(cfg->wall.kind));
  }
  return MPM_OK;
}

/* Region: a non-empty box; the flow-rate levels, if given, in order. */
static int check_region(in_ctx *c, const mpm_config *cfg)
{
  const char *pairs[][2] = {{"xmax", "xmin"}, {"ymax", "ymin"}};
  const double v[][2] = {{cfg->region.xmax, cfg->region.xmin}, {cfg->region.ymax, cfg->region.ymin}};
  for (int i = 0; i < 2; i++)
    if (!(v[i][0] > v[i][1])) {
      where w = mpm_io_in_blame(c, cfg, -1, key_index(S_REGION, pairs[i][0]),
                                key_index(S_REGION, pairs[i][1]));
      return mpm_io_in_fail_key(c, &w, "%s = %s <= %s = %s (allowed: %s > %s)", pairs[i][0],
                                mpm_io_in_num(v[i][0]).s, pairs[i][1], mpm_io_in_num(v[i][1]).s,
                                pairs[i][0], pairs[i][1]);
    }
  if (cfg->region.m_hi > 0.0 && !(cfg->region.m_hi > cfg->region.m_lo)) {
    where w = mpm_io_in_blame(c, cfg, -1, key_index(S_REGION, "m_hi"), key_index(S_REGION, "m_lo"));
    return mpm_io_in_fail_key(c, &w,
                              "m_hi = %s <= m_lo = %s (allowed: m_hi > m_lo, or m_hi = 0: no fit)",
                              mpm_io_in_num(cfg->region.m_hi).s, mpm_io_in_num(cfg->region.m_lo).s);
  }
  return MPM_OK;
}

/* A plane run: the 3D keys (but mesh.nz) set in a plain section, or in item
 * i of titled section t (t < 0: the plain sections). */
static int check_plane_keys(in_ctx *c, const mpm_config *cfg, int t, int i)
{
  const int knz = key_index(S_MESH, "nz");
  for (int k = 0; k < NKEYS; k++) {
    const int sec = mpm_io_in_keys[k].sec;
    if (!(mpm_io_in_keys[k].flags & KF_3D) || k == knz || mpm_io_in_titled_of(sec) != t ||
        !mpm_io_in_is_set(c, k, i))
      continue;
    where w = {.at = c->at[i < 0 ? 0 : i][k], .sec = sec, .key = k, .item = i,
               .title = t >= 0 ? mpm_io_in_title(cfg, t, i) : NULL};
    return mpm_io_in_fail_key(c, &w, "a key of 3D runs, set in a plane one (allowed: with "
                              "mesh.nz > 0 only)");
  }
  return MPM_OK;
}

/* A 3D run (mesh.nz > 0): the keys it needs (the z range of every fill
 * but a cylinder along x or y) and what is plane by nature (triangles); a
 * plane run: no 3D key set. */
static int check_dimension(in_ctx *c, const mpm_config *cfg)
{
  const int knz = key_index(S_MESH, "nz");
  if (cfg->mesh.nz == 0) {
    if (check_plane_keys(c, cfg, -1, -1) != MPM_OK)
      return MPM_EINPUT;
    for (int t = 0; t < NTITLED; t++)
      for (int i = 0; i < mpm_io_in_count_of(cfg, t); i++)
        if (check_plane_keys(c, cfg, t, i) != MPM_OK)
          return MPM_EINPUT;
    return MPM_OK;
  }
  const int kdz = key_index(S_MESH, "dz");
  if (!(cfg->mesh.dz > 0.0)) {
    where w = mpm_io_in_blame(c, cfg, -1, kdz, knz);
    return mpm_io_in_fail_key(c, &w, "nz = %d without dz (allowed: dz in %s ... %s m with "
                              "nz > 0)", cfg->mesh.nz, mpm_io_in_num(mpm_io_in_keys[kdz].lo).s,
                              mpm_io_in_num(mpm_io_in_keys[kdz].hi).s);
  }
  if ((cfg->mesh.nx + 1.0) * (cfg->mesh.ny + 1.0) * (cfg->mesh.nz + 1.0) > MAX_NODES) {
    where w = mpm_io_in_blame(c, cfg, -1, knz, knz);
    return mpm_io_in_fail_key(c, &w, "%d x %d x %d units make too many nodes (allowed: "
                              "(nx+1)(ny+1)(nz+1) <= %s)", cfg->mesh.nx, cfg->mesh.ny,
                              cfg->mesh.nz, mpm_io_in_num(MAX_NODES).s);
  }
  /* what the plane run has and the 3D one has not, by nature: named, not ignored */
  struct { int on; int sec; const char *key; const char *allowed; } no3[] = {
    {strcmp(cfg->mesh.topology, "q4") != 0, S_MESH, "topology", "\"q4\" (boxes)"},
  };
  for (size_t i = 0; i < sizeof no3 / sizeof no3[0]; i++) {
    if (!no3[i].on)
      continue;
    const int k = key_index(no3[i].sec, no3[i].key);
    where w = mpm_io_in_blame(c, cfg, -1, k, knz);
    return mpm_io_in_fail_key(c, &w, "not available in a 3D run (mesh.nz > 0) (allowed: %s)",
                              no3[i].allowed);
  }
  if (check_periodic_pair(c, cfg, "front", "back", cfg->bc.front, cfg->bc.back) != MPM_OK)
    return MPM_EINPUT;
  const double z1 = cfg->mesh.z0 + cfg->mesh.nz * cfg->mesh.dz, tol = GEOM_TOL * cfg->mesh.dz;
  const int kz0 = key_index(S_FILL, "zmin"), kz1 = key_index(S_FILL, "zmax");
  for (int f = 0; f < cfg->nfill; f++) {
    const mpm_fill_config *fc = &cfg->fill[f];
    if (!(mpm_io_in_keys[kz0].shapes & mpm_io_in_fill_form(fc, 1)))
      continue;  /* a cylinder along x or y: its span is its own (check_disc) */
    if (!mpm_io_in_is_set(c, kz0, f) || !mpm_io_in_is_set(c, kz1, f)) {
      const int km = mpm_io_in_is_set(c, kz0, f) ? kz1 : kz0;
      where w = {.at = c->at[f][km], .sec = S_FILL, .key = km, .item = f, .title = fc->name};
      return mpm_io_in_fail_key(c, &w, "required in a 3D run, not set (allowed: %s ... %s m)",
                                mpm_io_in_approx(cfg->mesh.z0).s, mpm_io_in_approx(z1).s);
    }
    if (!(fc->zmin < fc->zmax) || fc->zmin < cfg->mesh.z0 - tol || fc->zmax > z1 + tol) {
      where w = mpm_io_in_blame(c, cfg, f, kz1, kz0);
      return mpm_io_in_fail_key(c, &w, "the fill spans z %s ... %s (allowed: zmin < zmax "
                                "within %s ... %s m)", mpm_io_in_num(fc->zmin).s,
                                mpm_io_in_num(fc->zmax).s, mpm_io_in_approx(cfg->mesh.z0).s,
                                mpm_io_in_approx(z1).s);
    }
  }
  return MPM_OK;
}

int mpm_io_in_validate(in_ctx *c, mpm_config *cfg)
{
  if (check_required(c) != MPM_OK)
    return MPM_EINPUT;
  if (cfg->nfill == 0) {
    where w = {.sec = S_FILL, .key = -1, .item = -1};
    return mpm_io_in_fail_at(
        c, &w, "no fill section (allowed: 1 ... %d sections 'fill NAME { ... }')", MPM_MAX_FILLS);
  }
  resolve_scheme(c, cfg);
  if (check_mesh(c, cfg) || check_time(c, cfg) || check_gravity(c, cfg) ||
      check_material(c, cfg) || check_boundary(c, cfg) || check_outlet(c, cfg) ||
      check_wall(c, cfg) || check_region(c, cfg) || check_dimension(c, cfg))
    return MPM_EINPUT;
  resolve_stop(c, cfg);
  for (int i = 0; i < cfg->nfill; i++)
    if (mpm_io_in_check_fill(c, cfg, i) != MPM_OK)
      return MPM_EINPUT;
  for (int i = 0; i < cfg->nbody; i++)
    if (mpm_io_in_check_body(c, cfg, i) != MPM_OK)
      return MPM_EINPUT;
  return check_model(c, cfg);
}
