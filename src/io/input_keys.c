/* input_keys.c: the one table of input keys (section, type, default, allowed
 * range, unit, offset into mpm_config or the record of a titled section, the
 * forms of fill or body that use a key), the table of titled sections, and
 * the names each named key allows. The owning modules (mesh, shape,
 * material, bc with its bodies' shapes, sides and contacts, nonlocal)
 * decide which names are valid; the few name tables of the input itself
 * (fill shapes and cylinder axes, outlet edges, dilatation rules) live
 * here. */
#include <stddef.h>
#include <string.h>

#include "bc/bc.h"
#include "bc/body.h"
#include "core/names.h"
#include "io/input_internal.h"
#include "material/density.h"
#include "material/material.h"
#include "mesh/mesh.h"
#include "nonlocal/field.h"
#include "nonlocal/nonlocal.h"
#include "nonlocal/steady.h"
#include "shape/shape.h"

/* ------------------------------------------------------------ the key table */

const char *const mpm_io_in_sec_names[NSEC] = {
  "mesh", "time", "gravity", "material", "boundary", "fill", "body", "stop", "output", "outlet",
  "wall", "remove", "region", "absorb",
};

#define C_(m) offsetof(mpm_config, m)
#define F_(m) offsetof(mpm_fill_config, m)
#define B_(m) offsetof(mpm_body_config, m)
#define NUM(s, t, n, o, d, l, h, f, u) \
  {.name = n, .sec = s, .type = t, .off = o, .def = d, .lo = l, .hi = h, .flags = f, .unit = u}
#define NAMED(s, t, n, o, k, d) {.name = n, .sec = s, .type = t, .off = o, .kind = k, .sdef = d}
#define BODY(t, n, o, d, l, h, f, u) NUM(S_BODY, t, n, o, d, l, h, f, u)
/* a body's list: its values at o, their count at no */
#define BLIST(n, o, no, l, h, f, sh, u) \
  {.name = n, .sec = S_BODY, .type = KT_LIST, .off = B_(o), .noff = B_(no), .lo = l, .hi = h, \
   .flags = f, .shapes = sh, .unit = u}
#define GEOM(t, n, o, l, h, f, sh) \
  {.name = n, .sec = S_FILL, .type = t, .off = o, .lo = l, .hi = h, \
   .flags = KF_REQUIRED | (f), .shapes = sh, .unit = "m", .noff = F_(nvert)}

const key_def mpm_io_in_keys[] = {
    NUM(S_MESH, KT_INT, "nx", C_(mesh.nx), 0, 1, 100000, KF_REQUIRED, "-"),
    NUM(S_MESH, KT_INT, "ny", C_(mesh.ny), 0, 1, 100000, KF_REQUIRED, "-"),
    NUM(S_MESH, KT_REAL, "x0", C_(mesh.x0), 0, -1e9, 1e9, 0, "m"),
    NUM(S_MESH, KT_REAL, "y0", C_(mesh.y0), 0, -1e9, 1e9, 0, "m"),
    NUM(S_MESH, KT_REAL, "dx", C_(mesh.dx), 0, 1e-6, 1e6, KF_REQUIRED, "m"),
    NUM(S_MESH, KT_REAL, "dy", C_(mesh.dy), 0, 1e-6, 1e6, KF_REQUIRED, "m"),
    NUM(S_MESH, KT_INT, "nz", C_(mesh.nz), 0, 1, 100000, KF_ZERO_OFF | KF_3D, "-"),
    NUM(S_MESH, KT_REAL, "z0", C_(mesh.z0), 0, -1e9, 1e9, KF_3D, "m"),
    NUM(S_MESH, KT_REAL, "dz", C_(mesh.dz), 0, 1e-6, 1e6, KF_ZERO_OFF | KF_3D, "m"),
    NAMED(S_MESH, KT_NAME, "topology", C_(mesh.topology), NK_TOPOLOGY, "q4"),
    NAMED(S_MESH, KT_NAME, "diagonal", C_(mesh.diagonal), NK_DIAGONAL, "/"),
    NUM(S_MESH, KT_REAL, "mirror_x", C_(mesh.mirror_x), 0, -1e9, 1e9, 0, "m"),
    NAMED(S_MESH, KT_NAME, "shape", C_(mesh.shape), NK_SHAPE, "ugimp"),
    NAMED(S_MESH, KT_ENUM, "dilatation", C_(mesh.dilatation), NK_DILATATION, "element"),

    NUM(S_TIME, KT_REAL, "dt", C_(time.dt), 0, 1e-12, 1e6, KF_ZERO_OFF, "s"),
    NUM(S_TIME, KT_REAL, "cfl", C_(time.cfl), 0.5, 1e-6, 1, 0, "-"),
    NUM(S_TIME, KT_REAL, "t_end", C_(time.t_end), 0, 1e-9, 1e9, KF_REQUIRED, "s"),
    NUM(S_TIME, KT_REAL, "frame_dt", C_(time.frame_dt), 0.01, 1e-9, 1e9, 0, "s"),
    NUM(S_TIME, KT_REAL, "flip", C_(time.flip), 1, 0, 1, 0, "-"),
    NAMED(S_TIME, KT_ENUM, "transfer", C_(time.transfer), NK_TRANSFER, "apic"),
    NUM(S_TIME, KT_BOOL, "dt_unstable_ok", C_(time.dt_unstable_ok), 0, 0, 1, 0, "-"),

    NUM(S_GRAVITY, KT_REAL, "gx", C_(gravity.gx), 0, -1e5, 1e5, 0, "m/s^2"),
    NUM(S_GRAVITY, KT_REAL, "gy", C_(gravity.gy), -9.8, -1e5, 1e5, 0, "m/s^2"),
    NUM(S_GRAVITY, KT_REAL, "gz", C_(gravity.gz), 0, -1e5, 1e5, KF_3D, "m/s^2"),
    NUM(S_GRAVITY, KT_REAL, "angle", C_(gravity.angle), 0, -90, 90, 0, "deg"),
    NUM(S_GRAVITY, KT_REAL, "g", C_(gravity.g), 9.8, 0, 1e5, 0, "m/s^2"),
    NUM(S_GRAVITY, KT_REAL, "t_ramp", C_(gravity.t_ramp), 0.1, 0, 1e9, 0, "s"),

    NAMED(S_MATERIAL, KT_NAME, "model", C_(material.model), NK_MODEL, "mu_i"),
    NUM(S_MATERIAL, KT_REAL, "E", C_(material.E), 1e9, 1e3, 1e13, 0, "Pa"),
    NUM(S_MATERIAL, KT_REAL, "nu", C_(material.nu), MPM_DK15_NU, -1, 0.5, KF_LO_OPEN | KF_HI_OPEN,
        "-"),
    NUM(S_MATERIAL, KT_REAL, "rho_s", C_(material.rho_s), MPM_DK15_RHO_S, 1, 1e5, 0,
        "kg/m^3"),
    NUM(S_MATERIAL, KT_REAL, "rho_c", C_(material.rho_c), MPM_DK15_RHO_C, 1, 1e5, 0,
        "kg/m^3"),
    NUM(S_MATERIAL, KT_REAL, "mu_s", C_(material.mu_s), MPM_DK15_MU_S, 0, 10, 0, "-"),
    NUM(S_MATERIAL, KT_REAL, "mu_2", C_(material.mu_2), MPM_DK15_MU_2, 1e-6, 1000, 0, "-"),
    NUM(S_MATERIAL, KT_REAL, "I0", C_(material.I0), MPM_DK15_I0, 1e-6, 1000, 0, "-"),
    NUM(S_MATERIAL, KT_REAL, "d", C_(material.d), MPM_DK15_D, 1e-7, 1, 0, "m"),
    NUM(S_MATERIAL, KT_REAL, "A", C_(material.A), 0.48, 0, 100, 0, "-"),
    NUM(S_MATERIAL, KT_REAL, "t0", C_(material.t0), 1e-3, 1e-9, 1e3, 0, "s"),
    NAMED(S_MATERIAL, KT_ENUM, "form", C_(material.form), NK_NGF_FORM, "dk"),
    NAMED(S_MATERIAL, KT_ENUM, "p_sample", C_(material.p_sample), NK_NGF_P_SAMPLE, "point"),
    NAMED(S_MATERIAL, KT_ENUM, "g_average", C_(material.g_average), NK_NGF_G_AVERAGE, "centre"),
    NUM(S_MATERIAL, KT_REAL, "t_seed", C_(material.t_seed), 0, 0, 1e9, KF_T0X10, "s"),
    NAMED(S_MATERIAL, KT_ENUM, "diffusion", C_(material.diffusion), NK_DIFFUSION, "explicit"),
    NAMED(S_MATERIAL, KT_ENUM, "g_wall", C_(material.g_wall), NK_G_WALL, "dirichlet"),
    NAMED(S_MATERIAL, KT_ENUM, "g_sample", C_(material.g_sample), NK_G_SAMPLE, "element"),
    NAMED(S_MATERIAL, KT_ENUM, "g_mass", C_(material.g_mass), NK_G_MASS, "consistent"),
    NUM(S_MATERIAL, KT_INT, "n_sub", C_(material.n_sub), 1, 1, 1000000, 0, "-"),
    NUM(S_MATERIAL, KT_REAL, "dt_sub", C_(material.dt_sub), 0, 1e-12, 1e6, KF_ZERO_OFF, "s"),
    NAMED(S_MATERIAL, KT_ENUM, "state_density", C_(material.state_density), NK_DENSITY, "unit"),

    NAMED(S_BOUNDARY, KT_ENUM, "left", C_(bc.left), NK_BC, "free"),
    NAMED(S_BOUNDARY, KT_ENUM, "right", C_(bc.right), NK_BC, "free"),
    NAMED(S_BOUNDARY, KT_ENUM, "bottom", C_(bc.bottom), NK_BC, "free"),
    NAMED(S_BOUNDARY, KT_ENUM, "top", C_(bc.top), NK_BC, "free"),
    {.name = "front", .sec = S_BOUNDARY, .type = KT_ENUM, .off = C_(bc.front), .kind = NK_BC,
     .sdef = "free", .flags = KF_3D},
    {.name = "back", .sec = S_BOUNDARY, .type = KT_ENUM, .off = C_(bc.back), .kind = NK_BC,
     .sdef = "free", .flags = KF_3D},
    NAMED(S_BOUNDARY, KT_ENUM, "wall_acceleration", C_(bc.wall_acceleration), NK_WALL_ACC,
          "jump"),

    NAMED(S_FILL, KT_ENUM, "shape", F_(shape), NK_FILL_SHAPE, "rectangle"),
    /* a cylinder along an axis uses the span keys of that axis and the
       centre keys of the other two */
    GEOM(KT_REAL, "xmin", F_(xmin), -1e9, 1e9, 0, SH_RECT | SH_BOX | SH_CYL_X),
    GEOM(KT_REAL, "ymin", F_(ymin), -1e9, 1e9, 0, SH_RECT | SH_BOX | SH_CYL_Y),
    GEOM(KT_REAL, "xmax", F_(xmax), -1e9, 1e9, 0, SH_RECT | SH_BOX | SH_CYL_X),
    GEOM(KT_REAL, "ymax", F_(ymax), -1e9, 1e9, 0, SH_RECT | SH_BOX | SH_CYL_Y),
    GEOM(KT_REAL, "cx", F_(cx), -1e9, 1e9, 0, SH_DISC | SH_CYL_Y | SH_CYL_Z),
    GEOM(KT_REAL, "cy", F_(cy), -1e9, 1e9, 0, SH_DISC | SH_CYL_X | SH_CYL_Z),
    GEOM(KT_REAL, "radius", F_(radius), 1e-6, 1e9, 0, SH_DISC | SH_CYL),
    GEOM(KT_LIST, "x", F_(px), -1e9, 1e9, 0, SH_POLY | SH_PRISM),
    GEOM(KT_LIST, "y", F_(py), -1e9, 1e9, 0, SH_POLY | SH_PRISM),
    NUM(S_FILL, KT_INT, "ppu", F_(ppu), 2, 1, 8, 0, "-"),
    NUM(S_FILL, KT_REAL, "density", F_(density), 0, 1, 1e5, KF_RHO_C, "kg/m^3"),
    NUM(S_FILL, KT_REAL, "vx", F_(vx), 0, -1e4, 1e4, 0, "m/s"),
    NUM(S_FILL, KT_REAL, "vy", F_(vy), 0, -1e4, 1e4, 0, "m/s"),
    GEOM(KT_REAL, "zmin", F_(zmin), -1e9, 1e9, KF_3D, SH_BOX | SH_PRISM | SH_CYL_Z),
    GEOM(KT_REAL, "zmax", F_(zmax), -1e9, 1e9, KF_3D, SH_BOX | SH_PRISM | SH_CYL_Z),
    {.name = "axis", .sec = S_FILL, .type = KT_ENUM, .off = F_(axis), .kind = NK_FILL_AXIS,
     .sdef = "z", .flags = KF_3D, .shapes = SH_CYL},
    GEOM(KT_REAL, "cz", F_(cz), -1e9, 1e9, KF_3D, SH_CYL_X | SH_CYL_Y),
    NUM(S_FILL, KT_REAL, "vz", F_(vz), 0, -1e4, 1e4, KF_3D, "m/s"),
    NUM(S_FILL, KT_BOOL, "lithostatic", F_(lithostatic), 0, 0, 1, 0, "-"),
    NUM(S_FILL, KT_REAL, "k0", F_(k0), 0, 0.01, 10, KF_ZERO_OFF, "-"),
    NUM(S_FILL, KT_REAL, "pressure", F_(pressure), 0, 0, 1e9, 0, "Pa"),

    NAMED(S_BODY, KT_ENUM, "shape", B_(shape), NK_BODY_SHAPE, "disc"),
    {.name = "axis", .sec = S_BODY, .type = KT_ENUM, .off = B_(axis), .kind = NK_FILL_AXIS,
     .sdef = "z", .flags = KF_3D},
    BODY(KT_REAL, "cx", B_(cx), 0, -1e9, 1e9, KF_REQUIRED, "m"),
    BODY(KT_REAL, "cy", B_(cy), 0, -1e9, 1e9, KF_REQUIRED, "m"),
    BODY(KT_REAL, "cz", B_(cz), 0, -1e9, 1e9, KF_3D, "m"),
    {.name = "radius", .sec = S_BODY, .type = KT_REAL, .off = B_(radius), .lo = 1e-6, .hi = 1e9,
     .flags = KF_REQUIRED, .shapes = BS_DISC, .unit = "m"},
    {.name = "hx", .sec = S_BODY, .type = KT_REAL, .off = B_(hx), .lo = 1e-6, .hi = 1e9,
     .flags = KF_REQUIRED, .shapes = BS_BOX, .unit = "m"},
    {.name = "hy", .sec = S_BODY, .type = KT_REAL, .off = B_(hy), .lo = 1e-6, .hi = 1e9,
     .flags = KF_REQUIRED, .shapes = BS_BOX, .unit = "m"},
    BLIST("x", px, nvert, -1e9, 1e9, KF_REQUIRED, BS_POLY, "m"),
    BLIST("y", py, nvert, -1e9, 1e9, KF_REQUIRED, BS_POLY, "m"),
    BODY(KT_REAL, "angle", B_(angle), 0, -360, 360, 0, "deg"),
    BODY(KT_REAL, "length", B_(length), 0, 0, 1e9, KF_3D, "m"),
    NAMED(S_BODY, KT_ENUM, "side", B_(side), NK_BODY_SIDE, "outside"),
    NAMED(S_BODY, KT_ENUM, "contact", B_(contact), NK_BODY_CONTACT, "noslip"),
    BODY(KT_REAL, "friction", B_(friction), 0, 0, 10, 0, "-"),
    BLIST("t", t, ntable, 0, 1e9, KF_RISING, 0, "s"),
    BLIST("vx", val[MPM_BODY_VX], nval[MPM_BODY_VX], -1e4, 1e4, 0, 0, "m/s"),
    BLIST("vy", val[MPM_BODY_VY], nval[MPM_BODY_VY], -1e4, 1e4, 0, 0, "m/s"),
    BLIST("vz", val[MPM_BODY_VZ], nval[MPM_BODY_VZ], -1e4, 1e4, KF_3D, 0, "m/s"),
    BLIST("omega", val[MPM_BODY_OMEGA], nval[MPM_BODY_OMEGA], -1e4, 1e4, 0, 0, "rad/s"),
    BODY(KT_BOOL, "free_x", B_(free[MPM_BODY_VX]), 0, 0, 1, 0, "-"),
    BODY(KT_BOOL, "free_y", B_(free[MPM_BODY_VY]), 0, 0, 1, 0, "-"),
    BODY(KT_BOOL, "free_z", B_(free[MPM_BODY_VZ]), 0, 0, 1, KF_3D, "-"),
    BODY(KT_BOOL, "free_rotation", B_(free[MPM_BODY_OMEGA]), 0, 0, 1, 0, "-"),
    BODY(KT_REAL, "mass", B_(mass), 0, 0, 1e12, 0, "kg/m"),
    BODY(KT_REAL, "inertia", B_(inertia), 0, 0, 1e12, 0, "kg m^2/m"),
    BODY(KT_REAL, "fx", B_(force[0]), 0, -1e12, 1e12, 0, "N/m"),
    BODY(KT_REAL, "fy", B_(force[1]), 0, -1e12, 1e12, 0, "N/m"),
    BODY(KT_REAL, "fz", B_(force[2]), 0, -1e12, 1e12, KF_3D, "N/m"),
    BODY(KT_REAL, "torque", B_(torque), 0, -1e12, 1e12, 0, "N m/m"),
    BODY(KT_REAL, "damping", B_(damping), 0, 0, 1e6, 0, "1/s"),
    BODY(KT_BOOL, "carve", B_(carve), 0, 0, 1, 0, "-"),

    NUM(S_STOP, KT_REAL, "ke", C_(stop.ke), 0, 0, 1e9, 0, "J/kg"),
    NUM(S_STOP, KT_REAL, "t_min", C_(stop.t_min), 0, 0, 1e9, 0, "s"),
    NUM(S_STOP, KT_REAL, "mass", C_(stop.mass), 0, 0, 1e9, 0, "kg/m"),

    NAMED(S_OUTPUT, KT_PATH, "dir", C_(output.dir), NK_NONE, "run"),
    NUM(S_OUTPUT, KT_REAL, "checkpoint_dt", C_(output.checkpoint_dt), 0, 1e-9, 1e9, KF_ZERO_OFF,
        "s"),
    NUM(S_OUTPUT, KT_REAL, "checkpoint_wall", C_(output.checkpoint_wall), 0, 1, 1e9, KF_ZERO_OFF,
        "s"),
    NUM(S_OUTPUT, KT_BOOL, "allow_large", C_(output.allow_large), 0, 0, 1, 0, "-"),

    NAMED(S_OUTLET, KT_ENUM, "edge", C_(outlet.edge), NK_EDGE, "none"),
    NUM(S_OUTLET, KT_REAL, "from", C_(outlet.from), 0, -1e9, 1e9, 0, "m"),
    NUM(S_OUTLET, KT_REAL, "to", C_(outlet.to), 0, -1e9, 1e9, 0, "m"),
    NUM(S_OUTLET, KT_REAL, "from2", C_(outlet.from2), 0, -1e9, 1e9, KF_3D, "m"),
    NUM(S_OUTLET, KT_REAL, "to2", C_(outlet.to2), 0, -1e9, 1e9, KF_3D, "m"),
    {.name = "shape", .sec = S_OUTLET, .type = KT_ENUM, .off = C_(outlet.shape),
     .kind = NK_OUTLET_SHAPE, .sdef = "rectangle", .flags = KF_3D},
    NUM(S_OUTLET, KT_REAL, "t_open", C_(outlet.t_open), 0, 0, 1e9, 0, "s"),
    NAMED(S_OUTLET, KT_ENUM, "closed", C_(outlet.closed), NK_BC, "noslip"),
    NAMED(S_OUTLET, KT_ENUM, "ends", C_(outlet.ends), NK_OUTLET_ENDS, "free"),

    {.name = "x",
     .sec = S_WALL,
     .type = KT_LIST,
     .off = C_(wall.px),
     .noff = C_(wall.nvert),
     .lo = -1e9,
     .hi = 1e9,
     .unit = "m"},
    {.name = "y",
     .sec = S_WALL,
     .type = KT_LIST,
     .off = C_(wall.py),
     .noff = C_(wall.nvert),
     .lo = -1e9,
     .hi = 1e9,
     .unit = "m"},
    NAMED(S_WALL, KT_ENUM, "kind", C_(wall.kind), NK_BC, "noslip"),

    NUM(S_REMOVE, KT_REAL, "below", C_(remove.below), -1e9, -1e9, 1e9, 0, "m"),
    NUM(S_REMOVE, KT_BOOL, "free_edges", C_(remove.free_edges), 0, 0, 1, 0, "-"),

    NUM(S_REGION, KT_REAL, "xmin", C_(region.xmin), -1e9, -1e9, 1e9, 0, "m"),
    NUM(S_REGION, KT_REAL, "xmax", C_(region.xmax), 1e9, -1e9, 1e9, 0, "m"),
    NUM(S_REGION, KT_REAL, "ymin", C_(region.ymin), -1e9, -1e9, 1e9, 0, "m"),
    NUM(S_REGION, KT_REAL, "ymax", C_(region.ymax), 1e9, -1e9, 1e9, 0, "m"),
    NUM(S_REGION, KT_REAL, "m_hi", C_(region.m_hi), 0, 0, 1e9, 0, "kg/m"),
    NUM(S_REGION, KT_REAL, "m_lo", C_(region.m_lo), 0, 0, 1e9, 0, "kg/m"),

    NUM(S_ABSORB, KT_REAL, "above", C_(absorb.above), 1e9, -1e9, 1e9, 0, "m"),
    NUM(S_ABSORB, KT_REAL, "factor", C_(absorb.factor), 0, 0, 1, 0, "-"),
};

_Static_assert(sizeof mpm_io_in_keys / sizeof mpm_io_in_keys[0] == NKEYS,
               "NKEYS (input_internal.h) must count the rows of mpm_io_in_keys");

/* ------------------------------------------------------ titled sections */

const titled_def mpm_io_in_titled[NTITLED] = {
  [T_FILL] = {.sec = S_FILL, .max = MPM_MAX_FILLS, .count_off = C_(nfill), .array_off = C_(fill),
              .size = sizeof(mpm_fill_config), .name_off = F_(name)},
  [T_BODY] = {.sec = S_BODY, .max = MPM_MAX_BODIES, .count_off = C_(nbody), .array_off = C_(body),
              .size = sizeof(mpm_body_config), .name_off = B_(name)},
};

_Static_assert(MAX_ITEMS >= MPM_MAX_FILLS && MAX_ITEMS >= MPM_MAX_BODIES,
               "MAX_ITEMS must hold every titled section's items");

int mpm_io_in_titled_of(int sec)
{
  for (int t = 0; t < NTITLED; t++)
    if (mpm_io_in_titled[t].sec == sec)
      return t;
  return -1;
}

int *mpm_io_in_count(mpm_config *cfg, int t)
{
  return (int *)(void *)((char *)cfg + mpm_io_in_titled[t].count_off);
}

int mpm_io_in_count_of(const mpm_config *cfg, int t)
{
  return *(const int *)(const void *)((const char *)cfg + mpm_io_in_titled[t].count_off);
}

void *mpm_io_in_item(mpm_config *cfg, int t, int i)
{
  const titled_def *td = &mpm_io_in_titled[t];
  return (char *)cfg + td->array_off + (size_t)i * td->size;
}

const void *mpm_io_in_item_of(const mpm_config *cfg, int t, int i)
{
  const titled_def *td = &mpm_io_in_titled[t];
  return (const char *)cfg + td->array_off + (size_t)i * td->size;
}

const char *mpm_io_in_title(const mpm_config *cfg, int t, int i)
{
  return (const char *)mpm_io_in_item_of(cfg, t, i) + mpm_io_in_titled[t].name_off;
}

/* ------------------------------------------------------------- name tables */

static const char *const fill_shape_names[] = {
  [MPM_FILL_RECTANGLE] = "rectangle", [MPM_FILL_DISC] = "disc",
  [MPM_FILL_POLYGON] = "polygon",
};

/* mpm_fill_config.axis, mpm_body_config.axis */
static const char *const fill_axis_names[] = {"x", "y", "z"};

static const char *const edge_names[] = {
  [MPM_OUTLET_NONE] = "none", [MPM_OUTLET_LEFT] = "left", [MPM_OUTLET_RIGHT] = "right",
  [MPM_OUTLET_BOTTOM] = "bottom", [MPM_OUTLET_TOP] = "top", [MPM_OUTLET_FRONT] = "front",
  [MPM_OUTLET_BACK] = "back",
};

static const char *const outlet_shape_names[] = {
  [MPM_OUTLET_RECTANGLE] = "rectangle", [MPM_OUTLET_DISC] = "disc",
};

static const char *const dilatation_names[] = {
  [MPM_DILATATION_POINT] = "point", [MPM_DILATATION_UNIT] = "unit",
  [MPM_DILATATION_ELEMENT] = "element",
};

static const char *const outlet_ends_names[] = {
  [MPM_OUTLET_ENDS_FREE] = "free", [MPM_OUTLET_ENDS_FIXED] = "fixed",
};

static const char *const transfer_names[] = {
  [MPM_TRANSFER_FLIP] = "flip", [MPM_TRANSFER_APIC] = "apic",
};

/* Name <-> value of the config enums these tables cover. */
#define NAME_AT(table, i) mpm_names_at(table, MPM_NAMES_COUNT(table), i)
#define NAME_INDEX(table, s) mpm_names_index(table, MPM_NAMES_COUNT(table), s)

/* The i-th allowed name of a kind, NULL past the end. */
const char *mpm_io_in_name_at(int kind, int i)
{
  int j = 0;
  switch (kind) {
  case NK_TOPOLOGY: return mpm_mesh_topology_name(i);
  case NK_DIAGONAL: return mpm_mesh_diagonal_name(i);
  case NK_FILL_SHAPE: return NAME_AT(fill_shape_names, i);
  case NK_FILL_AXIS: return NAME_AT(fill_axis_names, i);
  case NK_BODY_SHAPE: return mpm_body_shape_name(i);
  case NK_BODY_SIDE: return mpm_body_side_name(i);
  case NK_BODY_CONTACT: return mpm_body_contact_name(i);
  case NK_EDGE: return NAME_AT(edge_names, i);
  case NK_OUTLET_SHAPE: return NAME_AT(outlet_shape_names, i);
  case NK_OUTLET_ENDS: return NAME_AT(outlet_ends_names, i);
  case NK_DILATATION: return NAME_AT(dilatation_names, i);
  case NK_TRANSFER: return NAME_AT(transfer_names, i);
  case NK_BC: return mpm_bc_kind_name(i);
  case NK_NGF_FORM: return mpm_material_ngf_form_name(i);
  case NK_NGF_P_SAMPLE: return mpm_material_ngf_p_sample_name(i);
  case NK_NGF_G_AVERAGE: return mpm_nonlocal_rule_name(i);
  case NK_DENSITY: return mpm_material_density_rule_name(i);
  case NK_DIFFUSION: return mpm_nonlocal_diffusion_name(i);
  case NK_G_WALL: return mpm_nonlocal_wall_name(i);
  case NK_WALL_ACC: return mpm_bc_wall_acceleration_name(i);
  case NK_G_SAMPLE: return mpm_nonlocal_steady_sample_name(i);
  case NK_G_MASS: return mpm_nonlocal_steady_mass_name(i);
  case NK_SHAPE:
    while (j < i && mpm_shape_table[j])
      j++;
    return mpm_shape_table[j] ? mpm_shape_table[j]->name : NULL;
  case NK_MODEL:
    while (j < i && mpm_material_table[j])
      j++;
    return mpm_material_table[j] ? mpm_material_table[j]->name : NULL;
  default: return NULL;
  }
}

/* Enum value of a name (0 for table names without one); -1 if not allowed.
 * The owning modules decide what is valid. */
int mpm_io_in_name_value(int kind, const char *s)
{
  switch (kind) {
  case NK_TOPOLOGY: return mpm_mesh_topology_from_name(s);
  case NK_DIAGONAL: return mpm_mesh_diagonal_from_name(s);
  case NK_SHAPE: return mpm_shape_lookup(s) ? 0 : -1;
  case NK_MODEL: return mpm_material_lookup(s) ? 0 : -1;
  case NK_BC: return mpm_bc_kind_from_name(s);
  case NK_FILL_SHAPE: return NAME_INDEX(fill_shape_names, s);
  case NK_FILL_AXIS: return NAME_INDEX(fill_axis_names, s);
  case NK_BODY_SHAPE: return mpm_body_shape_from_name(s);
  case NK_BODY_SIDE: return mpm_body_side_from_name(s);
  case NK_BODY_CONTACT: return mpm_body_contact_from_name(s);
  case NK_NGF_FORM: return mpm_material_ngf_form_from_name(s);
  case NK_NGF_P_SAMPLE: return mpm_material_ngf_p_sample_from_name(s);
  case NK_NGF_G_AVERAGE: return mpm_nonlocal_rule_from_name(s);
  case NK_DENSITY: return mpm_material_density_rule_from_name(s);
  case NK_DIFFUSION: return mpm_nonlocal_diffusion_from_name(s);
  case NK_G_WALL: return mpm_nonlocal_wall_from_name(s);
  case NK_WALL_ACC: return mpm_bc_wall_acceleration_from_name(s);
  case NK_G_SAMPLE: return mpm_nonlocal_steady_sample_from_name(s);
  case NK_G_MASS: return mpm_nonlocal_steady_mass_from_name(s);
  case NK_EDGE: return NAME_INDEX(edge_names, s);
  case NK_OUTLET_SHAPE: return NAME_INDEX(outlet_shape_names, s);
  case NK_OUTLET_ENDS: return NAME_INDEX(outlet_ends_names, s);
  case NK_DILATATION: return NAME_INDEX(dilatation_names, s);
  case NK_TRANSFER: return NAME_INDEX(transfer_names, s);
  default: return -1;
  }
}

int mpm_io_in_find_section(const char *name)
{
  for (int s = 0; s < NSEC; s++)
    if (strcmp(mpm_io_in_sec_names[s], name) == 0)
      return s;
  return -1;
}

int mpm_io_in_find_key(int sec, const char *name)
{
  for (int k = 0; k < NKEYS; k++)
    if (mpm_io_in_keys[k].sec == sec && strcmp(mpm_io_in_keys[k].name, name) == 0)
      return k;
  return -1;
}

/* The form of fill f (one SH_ bit) in a plane (dim3 = 0) or a 3D run; 0 for
 * a shape or an axis out of range. */
int mpm_io_in_fill_form(const mpm_fill_config *f, int dim3)
{
  switch (f->shape) {
  case MPM_FILL_RECTANGLE: return dim3 ? SH_BOX : SH_RECT;
  case MPM_FILL_POLYGON: return dim3 ? SH_PRISM : SH_POLY;
  case MPM_FILL_DISC:
    if (!dim3)
      return SH_DISC;
    return f->axis >= 0 && f->axis <= 2 ? SH_CYL_X << f->axis : 0;
  default: return 0;
  }
}

/* The form of item rec of titled section t (one bit of key_def.shapes), 0
 * for a section without forms. */
int mpm_io_in_item_form(int t, const void *rec, int dim3)
{
  switch (t) {
  case T_FILL: return mpm_io_in_fill_form(rec, dim3);
  case T_BODY: return mpm_io_in_body_form(rec);
  default: return 0;
  }
}

/* The form of body b (one BS_ bit, the same in a plane and a 3D run); 0 for
 * a shape out of range. */
int mpm_io_in_body_form(const mpm_body_config *b)
{
  return b->shape >= MPM_BODY_DISC && b->shape <= MPM_BODY_POLYGON ? 1 << b->shape : 0;
}
