/* input.c: input files (libconfuse) -> mpm_config: defaults, typed and
 * range-checked values, --set overrides, cross-field checks, and the writer
 * of the fully resolved input (docs/input-reference.md).
 *
 * One table, keys[], lists every key with its section, type, default, allowed
 * range, unit and offset into mpm_config (or mpm_fill_config for fill keys).
 * Defaults, parsing, overrides, the required-key check and the writer are all
 * driven by it; tests/test_input.c checks the reference page against it.
 *
 * libconfuse does the syntax (sections, titles, lists, quoting, comments,
 * ${ENV} substitution). Every key is a user-defined (CFGT_PTR) option whose
 * parse callback keeps the raw text and the line it was read on, so typing
 * and range checks happen here, with one message shape:
 *     FILE:LINE: key 'section.key': what is wrong (allowed: ...)
 * A key left at its default is reported at the line where its section opens
 * (the last line of the file if the section is absent); a value from --set
 * is reported as "--set 'section.key=value'". libconfuse's own complaints (syntax, unknown
 * keys) reach an error callback that rewrites them in the same shape. The
 * library has no user-data pointer, so the callback finds its context through
 * a hidden option present in every section; a value given to that option in a
 * file is rejected as an unknown key. Only the first error is kept. */
#include "io/io.h"

#include <confuse.h>
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bc/bc.h"
#include "material/material.h"
#include "mesh/mesh.h"
#include "nonlocal/nonlocal.h"
#include "shape/shape.h"

#define INPUT_MAX_BYTES (16L << 20)  /* larger input files are refused */
#define MAX_NODES 1e8                /* (nx + 1)(ny + 1) */
#define GEOM_TOL 1e-9                /* fills may overshoot the mesh by this many units */
#define CTX_KEY "granmpm-input-context"
#define SHOW_MAX 60                  /* user text longer than this is cut in messages */

/* ------------------------------------------------------------ the key table */

enum section {
  S_MESH, S_TIME, S_GRAVITY, S_MATERIAL, S_BOUNDARY, S_FILL, S_STOP, S_OUTPUT,
  S_OUTLET, S_WALL, S_REMOVE, S_REGION, NSEC
};

static const char *const sec_names[NSEC] = {
  "mesh", "time", "gravity", "material", "boundary", "fill", "stop", "output",
  "outlet", "wall", "remove", "region"
};

enum key_type {
  KT_INT,   /* int */
  KT_REAL,  /* double */
  KT_BOOL,  /* int 0/1, written true/false */
  KT_NAME,  /* char[MPM_NAME_MAX], one of a name table */
  KT_ENUM,  /* int, the index of a name in a name table */
  KT_PATH,  /* char[MPM_PATH_MAX] */
  KT_LIST   /* double[MPM_MAX_POLY], polygon coordinates */
};

enum name_kind {
  NK_NONE, NK_TOPOLOGY, NK_DIAGONAL, NK_SHAPE, NK_MODEL, NK_BC, NK_FILL_SHAPE, NK_NGF_FORM,
  NK_NGF_P_SAMPLE, NK_NGF_G_AVERAGE, NK_DENSITY, NK_EDGE, NK_DILATATION
};

enum key_flag {
  KF_REQUIRED = 1,  /* no default (fill keys: required by the shapes that use it) */
  KF_LO_OPEN = 2,   /* value > lo rather than >= lo */
  KF_HI_OPEN = 4,   /* value < hi rather than <= hi */
  KF_RHO_C = 8,     /* default: material.rho_c */
  KF_T0X10 = 16     /* default: 10 material.t0 */
};

/* Fill shapes that use a key (0: every shape). */
#define SH_RECT (1 << MPM_FILL_RECTANGLE)
#define SH_DISC (1 << MPM_FILL_DISC)
#define SH_POLY (1 << MPM_FILL_POLYGON)

typedef struct key_def {
  const char *name;
  unsigned char sec, type, kind, flags, shapes;
  size_t off;         /* into mpm_config, or mpm_fill_config for fill keys */
  double def, lo, hi; /* numeric default and range (list: range of each value) */
  const char *sdef;   /* default of names and paths */
  const char *unit;   /* "-": dimensionless */
} key_def;

#define C_(m) offsetof(mpm_config, m)
#define F_(m) offsetof(mpm_fill_config, m)
#define NUM(s, t, n, o, d, l, h, f, u) \
  {.name = n, .sec = s, .type = t, .off = o, .def = d, .lo = l, .hi = h, .flags = f, .unit = u}
#define NAMED(s, t, n, o, k, d) {.name = n, .sec = s, .type = t, .off = o, .kind = k, .sdef = d}
#define GEOM(t, n, o, l, h, f, sh) \
  {.name = n, .sec = S_FILL, .type = t, .off = o, .lo = l, .hi = h, \
   .flags = KF_REQUIRED | (f), .shapes = sh, .unit = "m"}

static const key_def keys[] = {
  NUM(S_MESH, KT_INT, "nx", C_(mesh.nx), 0, 1, 100000, KF_REQUIRED, "-"),
  NUM(S_MESH, KT_INT, "ny", C_(mesh.ny), 0, 1, 100000, KF_REQUIRED, "-"),
  NUM(S_MESH, KT_REAL, "x0", C_(mesh.x0), 0, -1e9, 1e9, 0, "m"),
  NUM(S_MESH, KT_REAL, "y0", C_(mesh.y0), 0, -1e9, 1e9, 0, "m"),
  NUM(S_MESH, KT_REAL, "dx", C_(mesh.dx), 0, 0, 1e6, KF_REQUIRED | KF_LO_OPEN, "m"),
  NUM(S_MESH, KT_REAL, "dy", C_(mesh.dy), 0, 0, 1e6, KF_REQUIRED | KF_LO_OPEN, "m"),
  NAMED(S_MESH, KT_NAME, "topology", C_(mesh.topology), NK_TOPOLOGY, "q4"),
  NAMED(S_MESH, KT_NAME, "diagonal", C_(mesh.diagonal), NK_DIAGONAL, "/"),
  NUM(S_MESH, KT_REAL, "mirror_x", C_(mesh.mirror_x), 0, -1e9, 1e9, 0, "m"),
  NAMED(S_MESH, KT_NAME, "shape", C_(mesh.shape), NK_SHAPE, "ugimp"),
  NAMED(S_MESH, KT_ENUM, "dilatation", C_(mesh.dilatation), NK_DILATATION, "point"),

  NUM(S_TIME, KT_REAL, "dt", C_(time.dt), 0, 0, 1e6, 0, "s"),
  NUM(S_TIME, KT_REAL, "cfl", C_(time.cfl), 0.5, 0, 1, KF_LO_OPEN, "-"),
  NUM(S_TIME, KT_REAL, "t_end", C_(time.t_end), 0, 0, 1e9, KF_REQUIRED | KF_LO_OPEN, "s"),
  NUM(S_TIME, KT_REAL, "frame_dt", C_(time.frame_dt), 0.01, 0, 1e9, KF_LO_OPEN, "s"),
  NUM(S_TIME, KT_REAL, "flip", C_(time.flip), 1, 0, 1, 0, "-"),

  NUM(S_GRAVITY, KT_REAL, "gx", C_(gravity.gx), 0, -1e5, 1e5, 0, "m/s^2"),
  NUM(S_GRAVITY, KT_REAL, "gy", C_(gravity.gy), -9.8, -1e5, 1e5, 0, "m/s^2"),
  NUM(S_GRAVITY, KT_REAL, "angle", C_(gravity.angle), 0, -90, 90, 0, "deg"),
  NUM(S_GRAVITY, KT_REAL, "g", C_(gravity.g), 9.8, 0, 1e5, 0, "m/s^2"),
  NUM(S_GRAVITY, KT_REAL, "t_ramp", C_(gravity.t_ramp), 0.1, 0, 1e9, 0, "s"),

  NAMED(S_MATERIAL, KT_NAME, "model", C_(material.model), NK_MODEL, "mu_i"),
  NUM(S_MATERIAL, KT_REAL, "E", C_(material.E), 1e9, 0, 1e13, KF_LO_OPEN, "Pa"),
  NUM(S_MATERIAL, KT_REAL, "nu", C_(material.nu), MPM_DK15_NU, -1, 0.5, KF_LO_OPEN | KF_HI_OPEN, "-"),
  NUM(S_MATERIAL, KT_REAL, "rho_s", C_(material.rho_s), MPM_DK15_RHO_S, 0, 1e5, KF_LO_OPEN, "kg/m^3"),
  NUM(S_MATERIAL, KT_REAL, "rho_c", C_(material.rho_c), MPM_DK15_RHO_C, 0, 1e5, KF_LO_OPEN, "kg/m^3"),
  NUM(S_MATERIAL, KT_REAL, "mu_s", C_(material.mu_s), MPM_DK15_MU_S, 0, 10, 0, "-"),
  NUM(S_MATERIAL, KT_REAL, "mu_2", C_(material.mu_2), MPM_DK15_MU_2, 0, 10, KF_LO_OPEN, "-"),
  NUM(S_MATERIAL, KT_REAL, "I0", C_(material.I0), MPM_DK15_I0, 0, 10, KF_LO_OPEN, "-"),
  NUM(S_MATERIAL, KT_REAL, "d", C_(material.d), MPM_DK15_D, 0, 1, KF_LO_OPEN, "m"),
  NUM(S_MATERIAL, KT_REAL, "A", C_(material.A), 0.48, 0, 100, 0, "-"),
  NUM(S_MATERIAL, KT_REAL, "t0", C_(material.t0), 1e-3, 0, 1e3, KF_LO_OPEN, "s"),
  NAMED(S_MATERIAL, KT_ENUM, "form", C_(material.form), NK_NGF_FORM, "dk"),
  NAMED(S_MATERIAL, KT_ENUM, "p_sample", C_(material.p_sample), NK_NGF_P_SAMPLE, "point"),
  NAMED(S_MATERIAL, KT_ENUM, "g_average", C_(material.g_average), NK_NGF_G_AVERAGE, "centre"),
  NUM(S_MATERIAL, KT_REAL, "t_seed", C_(material.t_seed), 0, 0, 1e9, KF_T0X10, "s"),
  NUM(S_MATERIAL, KT_INT, "n_sub", C_(material.n_sub), 1, 1, 1000000, 0, "-"),
  NUM(S_MATERIAL, KT_REAL, "dt_sub", C_(material.dt_sub), 0, 0, 1e6, 0, "s"),
  NAMED(S_MATERIAL, KT_ENUM, "state_density", C_(material.state_density), NK_DENSITY, "point"),

  NAMED(S_BOUNDARY, KT_ENUM, "left", C_(bc.left), NK_BC, "free"),
  NAMED(S_BOUNDARY, KT_ENUM, "right", C_(bc.right), NK_BC, "free"),
  NAMED(S_BOUNDARY, KT_ENUM, "bottom", C_(bc.bottom), NK_BC, "free"),
  NAMED(S_BOUNDARY, KT_ENUM, "top", C_(bc.top), NK_BC, "free"),

  NAMED(S_FILL, KT_ENUM, "shape", F_(shape), NK_FILL_SHAPE, "rectangle"),
  GEOM(KT_REAL, "xmin", F_(xmin), -1e9, 1e9, 0, SH_RECT),
  GEOM(KT_REAL, "ymin", F_(ymin), -1e9, 1e9, 0, SH_RECT),
  GEOM(KT_REAL, "xmax", F_(xmax), -1e9, 1e9, 0, SH_RECT),
  GEOM(KT_REAL, "ymax", F_(ymax), -1e9, 1e9, 0, SH_RECT),
  GEOM(KT_REAL, "cx", F_(cx), -1e9, 1e9, 0, SH_DISC),
  GEOM(KT_REAL, "cy", F_(cy), -1e9, 1e9, 0, SH_DISC),
  GEOM(KT_REAL, "radius", F_(radius), 0, 1e9, KF_LO_OPEN, SH_DISC),
  GEOM(KT_LIST, "x", F_(px), -1e9, 1e9, 0, SH_POLY),
  GEOM(KT_LIST, "y", F_(py), -1e9, 1e9, 0, SH_POLY),
  NUM(S_FILL, KT_INT, "ppu", F_(ppu), 2, 1, 8, 0, "-"),
  NUM(S_FILL, KT_REAL, "density", F_(density), 0, 0, 1e5, KF_LO_OPEN | KF_RHO_C, "kg/m^3"),
  NUM(S_FILL, KT_REAL, "vx", F_(vx), 0, -1e4, 1e4, 0, "m/s"),
  NUM(S_FILL, KT_REAL, "vy", F_(vy), 0, -1e4, 1e4, 0, "m/s"),
  NUM(S_FILL, KT_BOOL, "lithostatic", F_(lithostatic), 0, 0, 1, 0, "-"),

  NUM(S_STOP, KT_REAL, "ke", C_(stop.ke), 0, 0, 1e9, 0, "J/kg"),
  NUM(S_STOP, KT_REAL, "t_min", C_(stop.t_min), 0, 0, 1e9, 0, "s"),
  NUM(S_STOP, KT_REAL, "mass", C_(stop.mass), 0, 0, 1e9, 0, "kg/m"),

  NAMED(S_OUTPUT, KT_PATH, "dir", C_(output.dir), NK_NONE, "run"),

  NAMED(S_OUTLET, KT_ENUM, "edge", C_(outlet.edge), NK_EDGE, "none"),
  NUM(S_OUTLET, KT_REAL, "from", C_(outlet.from), 0, -1e9, 1e9, 0, "m"),
  NUM(S_OUTLET, KT_REAL, "to", C_(outlet.to), 0, -1e9, 1e9, 0, "m"),
  NUM(S_OUTLET, KT_REAL, "t_open", C_(outlet.t_open), 0, 0, 1e9, 0, "s"),
  NAMED(S_OUTLET, KT_ENUM, "closed", C_(outlet.closed), NK_BC, "noslip"),

  {.name = "x", .sec = S_WALL, .type = KT_LIST, .off = C_(wall.px), .lo = -1e9, .hi = 1e9,
   .unit = "m"},
  {.name = "y", .sec = S_WALL, .type = KT_LIST, .off = C_(wall.py), .lo = -1e9, .hi = 1e9,
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
};

#define NKEYS ((int)(sizeof keys / sizeof keys[0]))

/* ------------------------------------------------------------- name tables */

static const char *const fill_shape_names[] = {
  [MPM_FILL_RECTANGLE] = "rectangle", [MPM_FILL_DISC] = "disc",
  [MPM_FILL_POLYGON] = "polygon", [MPM_FILL_POLYGON + 1] = NULL
};

static const char *const edge_names[] = {
  [MPM_OUTLET_NONE] = "none", [MPM_OUTLET_LEFT] = "left", [MPM_OUTLET_RIGHT] = "right",
  [MPM_OUTLET_BOTTOM] = "bottom", [MPM_OUTLET_TOP] = "top", [MPM_OUTLET_TOP + 1] = NULL
};

static const char *const dilatation_names[] = {
  [MPM_DILATATION_POINT] = "point", [MPM_DILATATION_UNIT] = "unit",
  [MPM_DILATATION_UNIT + 1] = NULL
};

static int list_index(const char *const *list, const char *s)
{
  for (int i = 0; list[i]; i++)
    if (strcmp(list[i], s) == 0)
      return i;
  return -1;
}

/* The i-th allowed name of a kind, NULL past the end. */
static const char *name_at(int kind, int i)
{
  int j = 0;
  switch (kind) {
  case NK_TOPOLOGY: return mpm_mesh_topology_name(i);
  case NK_DIAGONAL: return mpm_mesh_diagonal_name(i);
  case NK_FILL_SHAPE: return i >= 0 && i <= MPM_FILL_POLYGON ? fill_shape_names[i] : NULL;
  case NK_EDGE: return i >= 0 && i <= MPM_OUTLET_TOP ? edge_names[i] : NULL;
  case NK_DILATATION: return i >= 0 && i <= MPM_DILATATION_UNIT ? dilatation_names[i] : NULL;
  case NK_BC: return mpm_bc_kind_name(i);
  case NK_NGF_FORM: return mpm_ngf_form_name(i);
  case NK_NGF_P_SAMPLE: return mpm_ngf_p_sample_name(i);
  case NK_NGF_G_AVERAGE: return mpm_nonlocal_rule_name(i);
  case NK_DENSITY: return mpm_density_rule_name(i);
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
static int name_value(int kind, const char *s)
{
  switch (kind) {
  case NK_TOPOLOGY: return mpm_mesh_topology_from_name(s);
  case NK_DIAGONAL: return mpm_mesh_diagonal_from_name(s);
  case NK_SHAPE: return mpm_shape_lookup(s) ? 0 : -1;
  case NK_MODEL: return mpm_material_lookup(s) ? 0 : -1;
  case NK_BC: return mpm_bc_kind_from_name(s);
  case NK_FILL_SHAPE: return list_index(fill_shape_names, s);
  case NK_NGF_FORM: return mpm_ngf_form_from_name(s);
  case NK_NGF_P_SAMPLE: return mpm_ngf_p_sample_from_name(s);
  case NK_NGF_G_AVERAGE: return mpm_nonlocal_rule_from_name(s);
  case NK_DENSITY: return mpm_density_rule_from_name(s);
  case NK_EDGE: return list_index(edge_names, s);
  case NK_DILATATION: return list_index(dilatation_names, s);
  default: return -1;
  }
}

/* --------------------------------------------------------- message pieces */

/* Texts returned by value, usable inline in a printf argument list: a word
 * (one number, name or cut user text) and a text (lists, messages). */
typedef struct word { char s[SHOW_MAX + 12]; } word;
typedef struct text { char s[MPM_ERR_MSG]; } text;

/* Append to t, cut at its end. */
static void addf(text *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void addf(text *t, const char *fmt, ...)
{
  size_t n = strlen(t->s);
  va_list ap;
  va_start(ap, fmt);
  vsnprintf(t->s + n, sizeof t->s - n, fmt, ap);
  va_end(ap);
}

/* User text for a message: cut to SHOW_MAX, control characters as '?'. */
static word show(const char *s)
{
  word w;
  size_t i = 0;
  for (; s[i] && i < SHOW_MAX; i++)
    w.s[i] = iscntrl((unsigned char)s[i]) ? '?' : s[i];
  if (s[i]) {
    memcpy(w.s + i, "...", 3);
    i += 3;
  }
  w.s[i] = '\0';
  return w;
}

/* v as written in messages and by the writer: integers below 1e6 in full,
 * otherwise the shortest "%g" text that reads back as v, with the exponent
 * trimmed ("1e9", "2.5e-7"). */
static word num(double v)
{
  word w, r = {{0}};
  if (v == floor(v) && fabs(v) < 1e6) {
    snprintf(w.s, sizeof w.s, "%.0f", v);
    return w;
  }
  for (int prec = 1; prec <= 17; prec++) {
    snprintf(w.s, sizeof w.s, "%.*g", prec, v);
    if (strtod(w.s, NULL) == v)
      break;
  }
  const char *e = strchr(w.s, 'e');
  if (!e)
    return w;
  size_t n = (size_t)(e - w.s) + 1;
  memcpy(r.s, w.s, n);
  const char *x = e + 1;
  if (*x == '-')
    r.s[n++] = '-';
  x += *x == '+' || *x == '-';
  while (*x == '0' && x[1])
    x++;
  memcpy(r.s + n, x, strlen(x) + 1);
  return r;
}

/* A computed value for a message, to 6 significant digits. */
static word approx(double v)
{
  word w;
  snprintf(w.s, sizeof w.s, "%.6g", v);
  return num(strtod(w.s, NULL));
}

/* A name as written in an input file: double quotes, '\' '"' '$' escaped. */
static word quoted(const char *s)
{
  word w;
  size_t n = 0;
  w.s[n++] = '"';
  for (; *s && n + 4 < sizeof w.s; s++) {
    if (*s == '"' || *s == '\\' || *s == '$')
      w.s[n++] = '\\';
    w.s[n++] = *s;
  }
  w.s[n++] = '"';
  w.s[n] = '\0';
  return w;
}

/* "q4", "t3", ... : the allowed names of a kind. */
static text name_list(int kind)
{
  text t = {{0}};
  const char *s;
  for (int i = 0; (s = name_at(kind, i)); i++)
    addf(&t, "%s%s", i ? ", " : "", quoted(s).s);
  return t;
}

static int has_unit(const key_def *kd)
{
  return kd->unit && kd->unit[0] && strcmp(kd->unit, "-") != 0;
}

/* The allowed range of a numeric key: "1 ... 8", "> 0 and <= 1e6 m". */
static text range_text(const key_def *kd)
{
  text t = {{0}};
  int lo_open = kd->flags & KF_LO_OPEN, hi_open = kd->flags & KF_HI_OPEN;
  if (!lo_open && !hi_open)
    addf(&t, "%s ... %s", num(kd->lo).s, num(kd->hi).s);
  else
    addf(&t, "%s %s and %s %s", lo_open ? ">" : ">=", num(kd->lo).s, hi_open ? "<" : "<=",
         num(kd->hi).s);
  if (has_unit(kd))
    addf(&t, " %s", kd->unit);
  return t;
}

/* What a key accepts, for "(allowed: ...)". */
static text allowed_text(const key_def *kd)
{
  text t = {{0}};
  switch (kd->type) {
  case KT_BOOL: addf(&t, "true, false, yes, no, on, off"); break;
  case KT_NAME:
  case KT_ENUM: t = name_list(kd->kind); break;
  case KT_PATH: addf(&t, "a path of 1 ... %d characters", MPM_PATH_MAX - 1); break;
  default: t = range_text(kd); break;
  }
  return t;
}

/* Comma-separated keys of a section (fill keys of some shapes if shapes != 0). */
static text key_list(int sec, int shapes)
{
  text t = {{0}};
  for (int k = 0; k < NKEYS; k++)
    if (keys[k].sec == sec && (!shapes || (keys[k].shapes & shapes)))
      addf(&t, "%s%s", t.s[0] ? ", " : "", keys[k].name);
  return t;
}

static text section_list(void)
{
  text t = {{0}};
  for (int s = 0; s < NSEC; s++)
    addf(&t, "%s%s", s ? ", " : "", sec_names[s]);
  return t;
}

static int find_section(const char *name)
{
  for (int s = 0; s < NSEC; s++)
    if (strcmp(sec_names[s], name) == 0)
      return s;
  return -1;
}

static int find_key(int sec, const char *name)
{
  for (int k = 0; k < NKEYS; k++)
    if (keys[k].sec == sec && strcmp(keys[k].name, name) == 0)
      return k;
  return -1;
}

/* --------------------------------------------------------- parse context */

/* Where a value came from: a file line, a --set (1 + its index), or neither
 * (the default). */
typedef struct loc {
  int line;
  int ovr;
} loc;

/* What an error is about. key < 0: a section as a whole; fill < 0: no fill. */
typedef struct where {
  loc at;
  int sec, key, fill;
  const char *title;  /* fill title in the key name; NULL: "fill.key" */
} where;

enum { SCAN_DEPTH = 64, MAX_BRACES = 128 };

typedef struct in_ctx {
  void *self;                    /* this context, read by the error callback */
  const char *path;
  const char *const *ovr;
  mpm_err *err;
  int failed;                    /* an error is recorded: keep the first */
  int eof_line;                  /* last line of the file */
  int sec_line[NSEC];            /* line of the section, 0: absent */
  int fill_line[MPM_MAX_FILLS];
  int sec_open[NSEC];            /* opening lines found by the comment scan */
  int fill_open[MPM_MAX_FILLS + 1];
  int nbrace;                    /* top-level '{' seen by the comment scan */
  size_t brace_pos[MAX_BRACES];
  int brace_line[MAX_BRACES];
  loc at[MPM_MAX_FILLS][NKEYS];  /* where each key was set (row 0: non-fill keys) */
  int nlist[MPM_MAX_FILLS][2];   /* number of polygon x and y values */
  int wall_nlist[2];             /* the same for the wall polygon */
  cfg_opt_t opts[NSEC + 1][NKEYS + 2];  /* libconfuse options: sections, root last */
} in_ctx;

static loc *loc_of(in_ctx *c, int key, int fill)
{
  return &c->at[fill < 0 ? 0 : fill][key];
}

static int is_set(const in_ctx *c, int key, int fill)
{
  const loc *l = &c->at[fill < 0 ? 0 : fill][key];
  return l->line > 0 || l->ovr > 0;
}

/* 1 if a was set after b (a --set counts after the file). */
static int later(loc a, loc b)
{
  if (a.ovr != b.ovr)
    return a.ovr > b.ovr;
  return a.line > b.line;
}

static int line_of(const in_ctx *c, const where *w)
{
  if (w->at.line > 0)
    return w->at.line;
  int line = 0;
  if (w->sec == S_FILL && w->fill >= 0)
    line = c->fill_line[w->fill];
  else if (w->sec >= 0 && w->sec != S_FILL)
    line = c->sec_line[w->sec];
  return line > 0 ? line : c->eof_line;
}

static text key_name(const where *w)
{
  text t = {{0}};
  const key_def *kd = &keys[w->key];
  if (kd->sec == S_FILL && w->title)
    addf(&t, "fill.%s.%s", show(w->title).s, kd->name);
  else
    addf(&t, "%s.%s", sec_names[kd->sec], kd->name);
  return t;
}

/* Messages are one line whatever the user wrote. */
static void one_line(mpm_err *err)
{
  if (err)
    for (char *p = err->msg; *p; p++)
      if (iscntrl((unsigned char)*p))
        *p = '?';
}

/* Record "LOCATION: [key 'NAME': ]message" (the first error only). */
static int failv(in_ctx *c, const where *w, int with_key, const char *fmt, va_list ap)
{
  if (c->failed)
    return MPM_EINPUT;
  c->failed = 1;
  char body[MPM_ERR_MSG], place[MPM_ERR_MSG];
  vsnprintf(body, sizeof body, fmt, ap);
  if (w->at.ovr > 0)
    snprintf(place, sizeof place, "--set '%s'", show(c->ovr[w->at.ovr - 1]).s);
  else
    snprintf(place, sizeof place, "%s:%d", c->path, line_of(c, w));
  if (with_key && w->key >= 0)
    mpm_err_set(c->err, MPM_EINPUT, "%s: key '%s': %s", place, key_name(w).s, body);
  else
    mpm_err_set(c->err, MPM_EINPUT, "%s: %s", place, body);
  one_line(c->err);
  return MPM_EINPUT;
}

static int fail_key(in_ctx *c, const where *w, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static int fail_at(in_ctx *c, const where *w, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

static int fail_key(in_ctx *c, const where *w, const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  int rc = failv(c, w, 1, fmt, ap);
  va_end(ap);
  return rc;
}

static int fail_at(in_ctx *c, const where *w, const char *fmt, ...)
{
  va_list ap;
  va_start(ap, fmt);
  int rc = failv(c, w, 0, fmt, ap);
  va_end(ap);
  return rc;
}

static int fail_range(in_ctx *c, const where *w, const char *value)
{
  return fail_key(c, w, "value %s out of range (allowed: %s)", show(value).s,
                  range_text(&keys[w->key]).s);
}

static text unknown_key_text(int sec, const char *title, const char *name)
{
  text t = {{0}};
  if (sec == S_FILL && title)
    addf(&t, "unknown key 'fill.%s.%s'", show(title).s, show(name).s);
  else
    addf(&t, "unknown key '%s.%s'", sec_names[sec], show(name).s);
  addf(&t, " (allowed keys in '%s': %s)", sec_names[sec], key_list(sec, 0).s);
  return t;
}

/* ------------------------------------------------------------ typed values */

static int starts_blank(const char *s)
{
  return *s == '\0' || isspace((unsigned char)*s);
}

/* 0: ok, 1: not an integer, 2: beyond long. */
static int parse_long(const char *s, long *v)
{
  char *end;
  if (starts_blank(s))
    return 1;
  errno = 0;
  *v = strtol(s, &end, 10);
  if (*end != '\0')
    return 1;
  return errno == ERANGE ? 2 : 0;
}

/* 0: ok (possibly non-finite), 1: not a number. */
static int parse_double(const char *s, double *v)
{
  char *end;
  if (starts_blank(s))
    return 1;
  *v = strtod(s, &end);
  return *end != '\0';
}

static int same_word(const char *a, const char *b)
{
  for (; *a && *b; a++, b++)
    if (tolower((unsigned char)*a) != *b)
      return 0;
  return *a == '\0' && *b == '\0';
}

static const char *const true_words[] = {"true", "yes", "on", NULL};
static const char *const false_words[] = {"false", "no", "off", NULL};

/* 0: ok, 1: not a boolean. */
static int parse_bool(const char *s, int *v)
{
  for (int i = 0; true_words[i]; i++) {
    if (same_word(s, true_words[i]) || same_word(s, false_words[i])) {
      *v = same_word(s, true_words[i]);
      return 0;
    }
  }
  return 1;
}

static int in_range(const key_def *kd, double v)
{
  if (!isfinite(v))
    return 0;
  if ((kd->flags & KF_LO_OPEN) ? v <= kd->lo : v < kd->lo)
    return 0;
  if ((kd->flags & KF_HI_OPEN) ? v >= kd->hi : v > kd->hi)
    return 0;
  return 1;
}

static int store_int(in_ctx *c, const where *w, const char *s, int *out)
{
  long v;
  int st = parse_long(s, &v);
  if (st == 1)
    return fail_key(c, w, "expected an integer, got '%s'", show(s).s);
  if (st == 2 || !in_range(&keys[w->key], (double)v))
    return fail_range(c, w, s);
  *out = (int)v;
  return MPM_OK;
}

static int store_real(in_ctx *c, const where *w, const char *s, double *out)
{
  double v;
  if (parse_double(s, &v))
    return fail_key(c, w, "expected a number, got '%s'", show(s).s);
  if (!in_range(&keys[w->key], v))
    return fail_range(c, w, s);
  *out = v;
  return MPM_OK;
}

static int store_bool(in_ctx *c, const where *w, const char *s, int *out)
{
  if (parse_bool(s, out))
    return fail_key(c, w, "expected true or false, got '%s' (allowed: %s)", show(s).s,
                    allowed_text(&keys[w->key]).s);
  return MPM_OK;
}

static void copy_text(char *dst, size_t cap, const char *s)
{
  memset(dst, 0, cap);
  memcpy(dst, s, strlen(s) < cap ? strlen(s) : cap - 1);
}

/* A name of a table: stored as text (KT_NAME) or as its enum value (KT_ENUM). */
static int store_name(in_ctx *c, const where *w, const char *s, char *out)
{
  const key_def *kd = &keys[w->key];
  int v = strlen(s) < MPM_NAME_MAX ? name_value(kd->kind, s) : -1;
  if (v < 0)
    return fail_key(c, w, "unknown value '%s' (allowed: %s)", show(s).s, name_list(kd->kind).s);
  if (kd->type == KT_ENUM)
    *(int *)out = v;
  else
    copy_text(out, MPM_NAME_MAX, s);
  return MPM_OK;
}

static int store_path(in_ctx *c, const where *w, const char *s, char *out)
{
  size_t n = strlen(s);
  if (n == 0 || n >= MPM_PATH_MAX)
    return fail_key(c, w, "%zu characters (allowed: a path of 1 ... %d characters)", n,
                    MPM_PATH_MAX - 1);
  for (const char *p = s; *p; p++)
    if (iscntrl((unsigned char)*p))
      return fail_key(c, w, "'%s' contains a control character (allowed: printable characters)",
                      show(s).s);
  copy_text(out, MPM_PATH_MAX, s);
  return MPM_OK;
}

/* Parse s as the value of key w->key into rec (mpm_config or mpm_fill_config). */
static int store_value(in_ctx *c, void *rec, const where *w, const char *s)
{
  const key_def *kd = &keys[w->key];
  char *p = (char *)rec + kd->off;
  int rc = MPM_EINPUT;
  switch (kd->type) {
  case KT_INT: rc = store_int(c, w, s, (int *)(void *)p); break;
  case KT_REAL: rc = store_real(c, w, s, (double *)(void *)p); break;
  case KT_BOOL: rc = store_bool(c, w, s, (int *)(void *)p); break;
  case KT_NAME:
  case KT_ENUM: rc = store_name(c, w, s, p); break;
  case KT_PATH: rc = store_path(c, w, s, p); break;
  default: break;
  }
  if (rc == MPM_OK)
    *loc_of(c, w->key, w->fill) = w->at;
  return rc;
}

/* Polygon coordinates: n values, each with its own location. */
static int store_list(in_ctx *c, void *rec, const where *w, const char *const *vals,
                      const loc *locs, int n)
{
  const key_def *kd = &keys[w->key];
  double *arr = (double *)(void *)((char *)rec + kd->off);
  if (n > MPM_MAX_POLY) {
    where e = *w;
    e.at = locs[MPM_MAX_POLY];
    return fail_key(c, &e, "more than %d values (allowed: 3 ... %d vertices)", MPM_MAX_POLY,
                    MPM_MAX_POLY);
  }
  memset(arr, 0, MPM_MAX_POLY * sizeof *arr);
  for (int i = 0; i < n; i++) {
    where e = *w;
    e.at = locs[i];
    if (store_real(c, &e, vals[i], &arr[i]) != MPM_OK)
      return MPM_EINPUT;
  }
  (w->fill < 0 ? c->wall_nlist : c->nlist[w->fill])[strcmp(kd->name, "x") == 0 ? 0 : 1] = n;
  *loc_of(c, w->key, w->fill) = n > 0 ? locs[0] : w->at;
  return MPM_OK;
}

static void store_default(void *rec, const key_def *kd)
{
  char *p = (char *)rec + kd->off;
  switch (kd->type) {
  case KT_INT:
  case KT_BOOL: *(int *)(void *)p = (int)kd->def; break;
  case KT_REAL: *(double *)(void *)p = kd->def; break;
  case KT_NAME: copy_text(p, MPM_NAME_MAX, kd->sdef); break;
  case KT_ENUM: *(int *)(void *)p = name_value(kd->kind, kd->sdef); break;
  case KT_PATH: copy_text(p, MPM_PATH_MAX, kd->sdef); break;
  default: break;
  }
}

static void fill_defaults(mpm_fill_config *f)
{
  memset(f, 0, sizeof *f);
  for (int k = 0; k < NKEYS; k++)
    if (keys[k].sec == S_FILL)
      store_default(f, &keys[k]);
}

/* ------------------------------------------------------- libconfuse glue */

/* A value as read: its text and the line it was on. */
typedef struct raw_value {
  int line;
  char text[];
} raw_value;

static int keep_raw(cfg_t *cfg, cfg_opt_t *opt, const char *value, void *result)
{
  if (cfg->name && strcmp(cfg->name, "root") == 0) {
    /* libconfuse reads "mesh|nx = 1" at the top level as mesh.nx: refuse */
    cfg_error(cfg, "no such option '%s'", opt->name);
    return -1;
  }
  size_t n = strlen(value);
  raw_value *r = malloc(sizeof *r + n + 1);
  if (!r) {
    cfg_error(cfg, "out of memory");
    return -1;
  }
  r->line = cfg->line;
  memcpy(r->text, value, n + 1);
  *(void **)result = r;
  return 0;
}

static int reject_value(cfg_t *cfg, cfg_opt_t *opt, const char *value, void *result)
{
  (void)value;
  (void)result;
  cfg_error(cfg, "no such option '%s'", opt->name);
  return -1;
}

static in_ctx *ctx_of(cfg_t *cfg)
{
  if (!cfg || !cfg->opts)
    return NULL;
  for (cfg_opt_t *o = cfg->opts; o->name; o++)
    if (strcmp(o->name, CTX_KEY) == 0 && o->simple_value.ptr)
      return *o->simple_value.ptr;
  return NULL;
}

static void unknown_option(in_ctx *c, const where *w, int sec, const char *title,
                           const char *name)
{
  if (sec >= 0) {
    fail_at(c, w, "%s", unknown_key_text(sec, title, name).s);
    return;
  }
  for (int k = 0; k < NKEYS; k++)
    if (strcmp(keys[k].name, name) == 0) {
      fail_at(c, w, "key '%s' outside a section (allowed: inside '%s { ... }')", show(name).s,
              sec_names[keys[k].sec]);
      return;
    }
  fail_at(c, w, "unknown section '%s' (allowed: %s)", show(name).s, section_list().s);
}

/* libconfuse's messages, rewritten; the formats are those of libconfuse 3.3. */
static void on_confuse_error(cfg_t *cfg, const char *fmt, va_list ap)
{
  in_ctx *c = ctx_of(cfg);
  if (!c || c->failed)
    return;
  int sec = cfg->name ? find_section(cfg->name) : -1;
  where w = {.at = {cfg->line > 0 ? cfg->line : 1, 0}, .sec = sec, .key = -1, .fill = -1};
  char msg[MPM_ERR_MSG];
  if (strcmp(fmt, "no such option '%s'") == 0) {
    unknown_option(c, &w, sec, cfg->title, va_arg(ap, const char *));
  } else if (strcmp(fmt, "missing title for section '%s'") == 0) {
    fail_at(c, &w, "section '%s' needs a title (allowed: %s NAME { ... })",
            show(va_arg(ap, const char *)).s, sec_names[S_FILL]);
  } else if (strcmp(fmt, "found duplicate title '%s'") == 0) {
    fail_at(c, &w, "a second fill titled '%s' (allowed: a different title for each fill)",
            show(va_arg(ap, const char *)).s);
  } else if (strcmp(fmt, "missing equal sign after option '%s'") == 0) {
    const char *k = va_arg(ap, const char *);
    w.key = sec >= 0 ? find_key(sec, k) : -1;
    w.title = cfg->title;
    fail_key(c, &w, "missing '=' (allowed: %s = value)", show(k).s);
  } else if (strcmp(fmt, "attempt to append to non-list option '%s'") == 0) {
    const char *k = va_arg(ap, const char *);
    w.key = sec >= 0 ? find_key(sec, k) : -1;
    w.title = cfg->title;
    fail_key(c, &w, "'+=' appends to lists only (allowed: %s = value)", show(k).s);
  } else {
    vsnprintf(msg, sizeof msg, fmt, ap);
    if (sec >= 0)
      fail_at(c, &w, "syntax error in section '%s': %s", sec_names[sec], msg);
    else
      fail_at(c, &w, "syntax error: %s", msg);
  }
}

static cfg_opt_t ptr_option(const char *name, int flags, cfg_callback_t parse)
{
  cfg_opt_t o;
  memset(&o, 0, sizeof o);
  o.name = name;
  o.type = CFGT_PTR;
  o.flags = flags;
  o.parsecb = parse;
  o.freecb = free;
  return o;
}

/* The hidden option through which on_confuse_error finds the context. */
static cfg_opt_t ctx_option(in_ctx *c)
{
  cfg_opt_t o = ptr_option(CTX_KEY, CFGF_NONE, reject_value);
  o.freecb = NULL;
  o.simple_value.ptr = &c->self;
  return o;
}

static void build_options(in_ctx *c)
{
  cfg_opt_t *root = c->opts[NSEC];
  for (int s = 0; s < NSEC; s++) {
    cfg_opt_t *o = c->opts[s];
    int n = 0;
    for (int k = 0; k < NKEYS; k++)
      if (keys[k].sec == s)
        o[n++] = ptr_option(keys[k].name, keys[k].type == KT_LIST ? CFGF_LIST : CFGF_NONE,
                            keep_raw);
    o[n++] = ctx_option(c);
    memset(&o[n], 0, sizeof o[n]);
    memset(&root[s], 0, sizeof root[s]);
    root[s].name = sec_names[s];
    root[s].type = CFGT_SEC;
    root[s].subopts = o;
    root[s].flags = s == S_FILL ? CFGF_MULTI | CFGF_TITLE | CFGF_NO_TITLE_DUPES : CFGF_NONE;
  }
  root[NSEC] = ctx_option(c);
  memset(&root[NSEC + 1], 0, sizeof root[NSEC + 1]);
}

/* ------------------------------------------------------------ reading text */

static int io_fail(mpm_err *err, int code, const char *path, const char *what, int e)
{
  mpm_err_set(err, code, "%s: %s: %s", path, what, strerror(e));
  one_line(err);
  return code;
}

static int read_text(const char *path, char **out, size_t *len, mpm_err *err)
{
  FILE *f = fopen(path, "rb");
  if (!f)
    return io_fail(err, MPM_EIO, path, "cannot open input file", errno);
  size_t cap = 4096, n = 0, got;
  char *buf = malloc(cap);
  while (buf && (got = fread(buf + n, 1, cap - n - 1, f)) > 0) {
    n += got;
    if (n + 1 == cap && (long)cap <= INPUT_MAX_BYTES) {
      char *bigger = realloc(buf, cap * 2);
      if (!bigger)
        free(buf);
      buf = bigger;
      cap *= 2;
    } else if (n + 1 == cap) {
      break;
    }
  }
  int e = errno, bad = ferror(f);
  fclose(f);
  if (!buf)
    return mpm_err_set(err, MPM_ENOMEM, "%s: out of memory reading the input file", path);
  if (bad) {
    free(buf);
    return io_fail(err, MPM_EIO, path, "cannot read input file", e);
  }
  if ((long)n > INPUT_MAX_BYTES) {
    free(buf);
    mpm_err_set(err, MPM_EINPUT, "%s: input file larger than %ld bytes (allowed: at most %ld)",
                path, INPUT_MAX_BYTES, INPUT_MAX_BYTES);
    one_line(err);
    return MPM_EINPUT;
  }
  buf[n] = '\0';
  *out = buf;
  *len = n;
  return MPM_OK;
}

static int line_at(const char *s, size_t pos)
{
  int line = 1;
  for (size_t i = 0; i < pos; i++)
    line += s[i] == '\n';
  return line;
}

enum scan_state { SC_CODE, SC_DQ, SC_SQ, SC_LINE, SC_BLOCK };

typedef struct scan {
  int state, line, from, depth;
  int open_line[SCAN_DEPTH];  /* line of each open '{' */
} scan;

/* A top-level '{': where sections open. */
static void note_section_brace(in_ctx *c, const char *s, const char *p, int line)
{
  if (c->nbrace < MAX_BRACES) {
    c->brace_pos[c->nbrace] = (size_t)(p - s);
    c->brace_line[c->nbrace++] = line;
  }
}

/* One character of code outside strings and comments; p may advance. A
 * comment opener is blanked here, the rest of the comment by the caller. */
static void scan_code(in_ctx *c, scan *sc, const char *s, char **pp)
{
  char *p = *pp;
  if (*p == '"' || *p == '\'') {
    sc->state = *p == '"' ? SC_DQ : SC_SQ;
    sc->from = sc->line;
  } else if (*p == '#' || (*p == '/' && p[1] == '/')) {
    sc->state = SC_LINE;
    *p = ' ';
  } else if (*p == '/' && p[1] == '*') {
    sc->state = SC_BLOCK;
    sc->from = sc->line;
    *p++ = ' ';
    *p = ' ';
  } else if (*p == '$' && p[1] == '{' && strchr(p, '}')) {
    for (const char *q = strchr(p, '}'); p < q; p++)  /* ${NAME}: one token */
      sc->line += *p == '\n';
  } else if (*p == '{') {
    if (sc->depth == 0)
      note_section_brace(c, s, p, sc->line);
    sc->open_line[sc->depth < SCAN_DEPTH ? sc->depth : SCAN_DEPTH - 1] = sc->line;
    sc->depth++;
  } else if (*p == '}' && sc->depth > 0) {
    sc->depth--;
  }
  *pp = p;
}

/* Comments are blanked (newlines kept) before libconfuse sees the text: its
 * 3.3 lexer counts the newline of a comment twice, so every later line number
 * would be off, and it rejects a comment inside a list. Outside quotes, '#',
 * '//' and slash-star start a comment anywhere. The same scan catches what
 * libconfuse 3.3 accepts silently: a section left open, and a comment left
 * open that hides the rest of the file (and open quotes, with their line). */
static int blank_comments(in_ctx *c, char *s)
{
  scan sc = {.state = SC_CODE, .line = 1};
  for (char *p = s; *p; p++) {
    if (sc.state == SC_CODE) {
      scan_code(c, &sc, s, &p);
    } else if (sc.state == SC_DQ || sc.state == SC_SQ) {
      if (*p == '\\' && p[1])
        p++;  /* an escaped character */
      else if (*p == (sc.state == SC_DQ ? '"' : '\''))
        sc.state = SC_CODE;
    } else if (*p == '\n') {
      sc.state = sc.state == SC_LINE ? SC_CODE : sc.state;
    } else if (sc.state == SC_BLOCK && *p == '*' && p[1] == '/') {
      sc.state = SC_CODE;
      *p++ = ' ';
      *p = ' ';
    } else {
      *p = ' ';
    }
    sc.line += *p == '\n';  /* a skipped first character is never a newline */
  }
  where w = {.at = {sc.from, 0}, .sec = -1, .key = -1, .fill = -1};
  if (sc.state == SC_BLOCK)
    return fail_at(c, &w, "comment '/*' is not closed (allowed: /* ... */)");
  if (sc.state == SC_DQ || sc.state == SC_SQ)
    return fail_at(c, &w, "quoted text is not closed (allowed: \"...\" or '...')");
  if (sc.depth > 0) {
    w.at.line = sc.open_line[sc.depth <= SCAN_DEPTH ? sc.depth - 1 : SCAN_DEPTH - 1];
    return fail_at(c, &w, "'{' is not closed (allowed: a matching '}')");
  }
  return MPM_OK;
}

static int is_word_char(char ch)
{
  return ch && !isspace((unsigned char)ch) && !strchr("#\"'={}()+,*", ch);
}

/* The word that ends before p (blanks skipped), as [start, *end); a quoted
 * word includes its quotes. */
static const char *word_before(const char *s, const char *p, const char **end)
{
  while (p > s && isspace((unsigned char)p[-1]))
    p--;
  *end = p;
  if (p > s && (p[-1] == '"' || p[-1] == '\'')) {
    char q = *--p;
    while (p > s && p[-1] != q)
      p--;
    return p > s ? p - 1 : p;
  }
  while (p > s && is_word_char(p[-1]))
    p--;
  return p;
}

static int word_is(const char *w, const char *end, const char *name)
{
  return (size_t)(end - w) == strlen(name) && strncmp(w, name, strlen(name)) == 0;
}

/* The opening lines of the sections ("NAME {" or "fill TITLE {"), in the order
 * libconfuse keeps them: the first of a repeated section, every fill. */
static void find_section_lines(in_ctx *c, const char *s)
{
  int nfill = 0;
  for (int b = 0; b < c->nbrace; b++) {
    const char *e1, *e2, *w1 = word_before(s, s + c->brace_pos[b], &e1);
    const char *w2 = word_before(s, w1, &e2);
    if (word_is(w2, e2, sec_names[S_FILL])) {
      if (nfill < MPM_MAX_FILLS + 1)
        c->fill_open[nfill++] = c->brace_line[b];
      continue;
    }
    for (int k = 0; k < NSEC; k++)
      if (k != S_FILL && word_is(w1, e1, sec_names[k]) && !c->sec_open[k])
        c->sec_open[k] = c->brace_line[b];
  }
}

static int parse_text(in_ctx *c, char *s, size_t len, cfg_t **root)
{
  const char *nul = memchr(s, '\0', len);
  if (nul) {
    where w = {.at = {line_at(s, (size_t)(nul - s)), 0}, .sec = -1, .key = -1, .fill = -1};
    return fail_at(c, &w, "NUL byte in the input file (allowed: text)");
  }
  int lines = line_at(s, len) - (len > 0 && s[len - 1] == '\n');
  c->eof_line = lines > 0 ? lines : 1;
  if (blank_comments(c, s) != MPM_OK)
    return MPM_EINPUT;
  find_section_lines(c, s);
  build_options(c);
  *root = cfg_init(c->opts[NSEC], CFGF_NONE);
  if (!*root)
    return mpm_err_set(c->err, MPM_ENOMEM, "%s: out of memory", c->path);
  cfg_set_error_function(*root, on_confuse_error);
  if (cfg_parse_buf(*root, s) != CFG_SUCCESS) {
    where w = {.at = {c->eof_line, 0}, .sec = -1, .key = -1, .fill = -1};
    return fail_at(c, &w, "syntax error");  /* kept only if nothing was said */
  }
  return MPM_OK;
}

/* ------------------------------------------------------ values from files */

static int collect_list(in_ctx *c, void *rec, const where *w, cfg_opt_t *o)
{
  const char *vals[MPM_MAX_POLY + 1];
  loc locs[MPM_MAX_POLY + 1];
  int n = (int)cfg_opt_size(o);
  for (int i = 0; i < n && i <= MPM_MAX_POLY; i++) {
    const raw_value *r = cfg_opt_getnptr(o, (unsigned)i);
    vals[i] = r->text;
    locs[i] = (loc){r->line, 0};
  }
  return store_list(c, rec, w, vals, locs, n);
}

static int collect_section(in_ctx *c, cfg_t *sec, int s, int fill, void *rec, const char *title)
{
  for (int k = 0; k < NKEYS; k++) {
    if (keys[k].sec != s)
      continue;
    cfg_opt_t *o = cfg_getopt(sec, keys[k].name);
    if (cfg_opt_size(o) == 0)
      continue;
    where w = {.sec = s, .key = k, .fill = fill, .title = title};
    int rc;
    if (keys[k].type == KT_LIST) {
      rc = collect_list(c, rec, &w, o);
    } else {
      const raw_value *r = cfg_opt_getnptr(o, 0);
      w.at.line = r->line;
      rc = store_value(c, rec, &w, r->text);
    }
    if (rc != MPM_OK)
      return rc;
  }
  return MPM_OK;
}

static int valid_title(const char *t)
{
  size_t n = strlen(t);
  if (n == 0 || n >= MPM_NAME_MAX)
    return 0;
  for (; *t; t++)
    if (!isalnum((unsigned char)*t) && *t != '_' && *t != '-')
      return 0;
  return 1;
}

static int collect_fills(in_ctx *c, cfg_t *root, mpm_config *cfg)
{
  unsigned n = cfg_size(root, sec_names[S_FILL]);
  for (unsigned i = 0; i < n; i++) {
    cfg_t *sec = cfg_getnsec(root, sec_names[S_FILL], i);
    const char *title = cfg_title(sec) ? cfg_title(sec) : "";
    int line = i <= MPM_MAX_FILLS && c->fill_open[i] ? c->fill_open[i] : sec->line;
    where w = {.at = {line, 0}, .sec = S_FILL, .key = -1, .fill = -1};
    if (i == MPM_MAX_FILLS)
      return fail_at(c, &w, "fill '%s' is fill number %u (allowed: at most %d fill sections)",
                     show(title).s, i + 1, MPM_MAX_FILLS);
    if (!valid_title(title))
      return fail_at(c, &w, "fill title '%s' (allowed: 1 ... %d letters, digits, '_' or '-')",
                     show(title).s, MPM_NAME_MAX - 1);
    c->fill_line[i] = line;
    fill_defaults(&cfg->fill[i]);
    copy_text(cfg->fill[i].name, MPM_NAME_MAX, title);
    cfg->nfill = (int)i + 1;
    if (collect_section(c, sec, S_FILL, (int)i, &cfg->fill[i], cfg->fill[i].name) != MPM_OK)
      return MPM_EINPUT;
  }
  return MPM_OK;
}

static int collect(in_ctx *c, cfg_t *root, mpm_config *cfg)
{
  for (int s = 0; s < NSEC; s++) {
    if (s == S_FILL)
      continue;
    cfg_t *sec = cfg_getsec(root, sec_names[s]);
    c->sec_line[s] = c->sec_open[s] ? c->sec_open[s] : sec ? sec->line : 0;
    if (sec && collect_section(c, sec, s, -1, cfg, NULL) != MPM_OK)
      return MPM_EINPUT;
  }
  return collect_fills(c, root, cfg);
}

/* -------------------------------------------------------------- overrides */

static char *trim(char *s)
{
  while (isspace((unsigned char)*s))
    s++;
  char *e = s + strlen(s);
  while (e > s && isspace((unsigned char)e[-1]))
    *--e = '\0';
  return s;
}

/* One pair of matching quotes around a --set value is dropped. */
static char *unquote(char *v)
{
  size_t n = strlen(v);
  if (n >= 2 && (v[0] == '"' || v[0] == '\'') && v[n - 1] == v[0]) {
    v[n - 1] = '\0';
    return v + 1;
  }
  return v;
}

/* "{1, 2, 3}" or "1, 2, 3" from a --set. */
static int override_list(in_ctx *c, void *rec, const where *w, char *v)
{
  const char *vals[MPM_MAX_POLY + 1];
  loc locs[MPM_MAX_POLY + 1];
  size_t n = strlen(v);
  if (n >= 2 && v[0] == '{' && v[n - 1] == '}') {
    v[n - 1] = '\0';
    v++;
  }
  int count = 0;
  for (char *p = v; count <= MPM_MAX_POLY;) {
    char *comma = strchr(p, ',');
    if (comma)
      *comma = '\0';
    vals[count] = unquote(trim(p));
    locs[count++] = w->at;
    if (!comma)
      break;
    p = comma + 1;
  }
  if (count == 1 && vals[0][0] == '\0')
    count = 0;
  return store_list(c, rec, w, vals, locs, count);
}

static int override_value(in_ctx *c, void *rec, const where *w, char *v)
{
  char *copy = malloc(strlen(v) + 1);
  if (!copy)
    return mpm_err_set(c->err, MPM_ENOMEM, "--set: out of memory");
  strcpy(copy, v);
  int rc = keys[w->key].type == KT_LIST ? override_list(c, rec, w, copy)
                                        : store_value(c, rec, w, unquote(copy));
  free(copy);
  return rc;
}

static int fill_index(const mpm_config *cfg, const char *title)
{
  for (int i = 0; i < cfg->nfill; i++)
    if (strcmp(cfg->fill[i].name, title) == 0)
      return i;
  return -1;
}

static text fill_titles(const mpm_config *cfg)
{
  text t = {{0}};
  for (int i = 0; i < cfg->nfill; i++)
    addf(&t, "%s%s", i ? ", " : "", cfg->fill[i].name);
  if (cfg->nfill == 0)
    addf(&t, "the file has no fill section");
  return t;
}

/* A fill key: "fill.KEY" sets it in every fill, "fill.TITLE.KEY" in one. */
static int override_fill(in_ctx *c, mpm_config *cfg, where *w, char *rest, char *v)
{
  char *dot = strrchr(rest, '.'), *key = dot ? dot + 1 : rest;
  if (dot)
    *dot = '\0';
  w->key = find_key(S_FILL, key);
  w->title = dot ? rest : NULL;
  if (w->key < 0)
    return fail_at(c, w, "%s", unknown_key_text(S_FILL, w->title, key).s);
  if (dot) {
    w->fill = fill_index(cfg, rest);
    if (w->fill < 0)
      return fail_at(c, w, "no fill titled '%s' (allowed: %s)", show(rest).s, fill_titles(cfg).s);
    return override_value(c, &cfg->fill[w->fill], w, v);
  }
  for (w->fill = 0; w->fill < cfg->nfill; w->fill++)
    if (override_value(c, &cfg->fill[w->fill], w, v) != MPM_OK)
      return MPM_EINPUT;
  return MPM_OK;
}

static int apply_override(in_ctx *c, mpm_config *cfg, int i, char *arg)
{
  where w = {.at = {0, i + 1}, .sec = -1, .key = -1, .fill = -1};
  char *eq = strchr(arg, '=');
  if (!eq)
    return fail_at(c, &w, "expected section.key=value");
  *eq = '\0';
  char *name = trim(arg), *v = trim(eq + 1), *dot = strchr(name, '.');
  if (!dot)
    return fail_at(c, &w, "'%s' is not section.key (allowed sections: %s)", show(name).s,
                   section_list().s);
  *dot = '\0';
  w.sec = find_section(name);
  if (w.sec < 0)
    return fail_at(c, &w, "unknown section '%s' (allowed: %s)", show(name).s, section_list().s);
  if (w.sec == S_FILL)
    return override_fill(c, cfg, &w, dot + 1, v);
  w.key = find_key(w.sec, dot + 1);
  if (w.key < 0)
    return fail_at(c, &w, "%s", unknown_key_text(w.sec, NULL, dot + 1).s);
  return override_value(c, cfg, &w, v);
}

static int apply_overrides(in_ctx *c, mpm_config *cfg, int n)
{
  for (int i = 0; i < n; i++) {
    if (!c->ovr[i])
      return mpm_err_set(c->err, MPM_EINVAL, "--set number %d is missing", i + 1);
    char *arg = malloc(strlen(c->ovr[i]) + 1);
    if (!arg)
      return mpm_err_set(c->err, MPM_ENOMEM, "--set: out of memory");
    strcpy(arg, c->ovr[i]);
    int rc = apply_override(c, cfg, i, arg);
    free(arg);
    if (rc != MPM_OK)
      return rc;
  }
  return MPM_OK;
}

/* ------------------------------------------------------ cross-field checks */

/* Where to report a relation between keys a and b: the one set last. */
static where blame(const in_ctx *c, const mpm_config *cfg, int fill, int a, int b)
{
  const loc *la = &c->at[fill < 0 ? 0 : fill][a], *lb = &c->at[fill < 0 ? 0 : fill][b];
  int k = later(*lb, *la) ? b : a;
  where w = {.at = k == a ? *la : *lb, .sec = keys[k].sec, .key = k, .fill = fill,
             .title = fill >= 0 ? cfg->fill[fill].name : NULL};
  return w;
}

static int key_index(int sec, const char *name)
{
  return find_key(sec, name);  /* the table is fixed: names used here exist */
}

static int check_required(in_ctx *c)
{
  for (int k = 0; k < NKEYS; k++) {
    if (keys[k].sec == S_FILL || !(keys[k].flags & KF_REQUIRED) || is_set(c, k, -1))
      continue;
    where w = {.sec = keys[k].sec, .key = k, .fill = -1};
    return fail_key(c, &w, "required, not set (allowed: %s)", allowed_text(&keys[k]).s);
  }
  return MPM_OK;
}

static int check_mesh(in_ctx *c, const mpm_config *cfg)
{
  double nodes = (cfg->mesh.nx + 1.0) * (cfg->mesh.ny + 1.0);
  if (nodes > MAX_NODES) {
    where w = blame(c, cfg, -1, key_index(S_MESH, "nx"), key_index(S_MESH, "ny"));
    return fail_key(c, &w, "%d x %d units make %s nodes (allowed: (nx+1)(ny+1) <= %s)",
                    cfg->mesh.nx, cfg->mesh.ny, num(nodes).s, num(MAX_NODES).s);
  }
  if (cfg->mesh.dilatation == MPM_DILATATION_UNIT &&
      (strcmp(cfg->mesh.shape, "delta") != 0 || strcmp(cfg->mesh.topology, "q4") != 0)) {
    const int ks = key_index(S_MESH, "shape"), kt = key_index(S_MESH, "topology");
    where w = blame(c, cfg, -1, key_index(S_MESH, "dilatation"),
                    strcmp(cfg->mesh.shape, "delta") != 0 ? ks : kt);
    return fail_key(c, &w, "dilatation = \"unit\" with shape = \"%s\", topology = \"%s\" "
                    "(allowed: shape = \"delta\" and topology = \"q4\")",
                    cfg->mesh.shape, cfg->mesh.topology);
  }
  double x1 = cfg->mesh.x0 + cfg->mesh.nx * cfg->mesh.dx, tol = GEOM_TOL * cfg->mesh.dx;
  double m = cfg->mesh.mirror_x;
  if (strcmp(cfg->mesh.diagonal, "mirror") == 0 && (m < cfg->mesh.x0 - tol || m > x1 + tol)) {
    where w = blame(c, cfg, -1, key_index(S_MESH, "mirror_x"), key_index(S_MESH, "diagonal"));
    return fail_key(c, &w, "mirror_x = %s lies outside the mesh (allowed: %s ... %s m)",
                    num(m).s, approx(cfg->mesh.x0).s, approx(x1).s);
  }
  return MPM_OK;
}

static int check_time(in_ctx *c, const mpm_config *cfg)
{
  if (cfg->time.frame_dt > cfg->time.t_end) {
    where w = blame(c, cfg, -1, key_index(S_TIME, "frame_dt"), key_index(S_TIME, "t_end"));
    return fail_key(c, &w, "frame_dt = %s > t_end = %s (allowed: frame_dt <= t_end)",
                    num(cfg->time.frame_dt).s, num(cfg->time.t_end).s);
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
  const int polar = is_set(c, ka, -1) ? ka : is_set(c, kg, -1) ? kg : -1;
  const int cart = is_set(c, kx, -1) ? kx : is_set(c, ky, -1) ? ky : -1;
  cfg->gravity.use_angle = polar >= 0;
  if (polar < 0)
    return MPM_OK;
  if (cart >= 0) {
    where w = blame(c, cfg, -1, polar, cart);
    return fail_key(c, &w, "gravity given both as gx, gy and as angle, g "
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
  if (!is_set(c, key_index(S_STOP, "t_min"), -1))
    cfg->stop.t_min = cfg->gravity.t_ramp;
}

static int check_material(in_ctx *c, mpm_config *cfg)
{
  for (int k = 0; k < NKEYS; k++)  /* NGF seeding time: 10 t0 unless given ([DK-silo] 6) */
    if ((keys[k].flags & KF_T0X10) && !is_set(c, k, -1))
      *(double *)(void *)((char *)cfg + keys[k].off) = 10.0 * cfg->material.t0;
  if (cfg->material.rho_c > cfg->material.rho_s) {
    where w = blame(c, cfg, -1, key_index(S_MATERIAL, "rho_c"), key_index(S_MATERIAL, "rho_s"));
    return fail_key(c, &w, "rho_c = %s > rho_s = %s (allowed: rho_c <= rho_s)",
                    num(cfg->material.rho_c).s, num(cfg->material.rho_s).s);
  }
  const int kn = key_index(S_MATERIAL, "n_sub"), kd = key_index(S_MATERIAL, "dt_sub");
  if (cfg->material.n_sub > 1 && cfg->material.dt_sub > 0.0) {  /* two ways to say it */
    where w = blame(c, cfg, -1, kd, kn);
    return fail_key(c, &w, "n_sub = %d with dt_sub = %s s (allowed: n_sub = 1 or dt_sub = 0)",
                    cfg->material.n_sub, num(cfg->material.dt_sub).s);
  }
  if (cfg->material.mu_s >= cfg->material.mu_2) {
    where w = blame(c, cfg, -1, key_index(S_MATERIAL, "mu_s"), key_index(S_MATERIAL, "mu_2"));
    return fail_key(c, &w, "mu_s = %s >= mu_2 = %s (allowed: mu_s < mu_2)",
                    num(cfg->material.mu_s).s, num(cfg->material.mu_2).s);
  }
  return MPM_OK;
}

static int check_periodic_pair(in_ctx *c, const mpm_config *cfg, const char *a, const char *b,
                               int ka, int kb)
{
  int pa = ka == MPM_BC_PERIODIC, pb = kb == MPM_BC_PERIODIC;
  if (pa == pb)
    return MPM_OK;
  where w = blame(c, cfg, -1, key_index(S_BOUNDARY, a), key_index(S_BOUNDARY, b));
  return fail_key(c, &w, "%s = \"%s\" but %s = \"%s\" (allowed: %s and %s both \"periodic\" or neither)",
                  a, mpm_bc_kind_name(ka), b, mpm_bc_kind_name(kb), a, b);
}

static int check_boundary(in_ctx *c, const mpm_config *cfg)
{
  if (check_periodic_pair(c, cfg, "left", "right", cfg->bc.left, cfg->bc.right) != MPM_OK)
    return MPM_EINPUT;
  return check_periodic_pair(c, cfg, "bottom", "top", cfg->bc.bottom, cfg->bc.top);
}

/* Keys of another shape must not be set; the shape's own required keys must. */
static int check_fill_keys(in_ctx *c, const mpm_config *cfg, int i)
{
  const mpm_fill_config *f = &cfg->fill[i];
  int mask = 1 << f->shape;
  const char *shape = fill_shape_names[f->shape];
  for (int k = 0; k < NKEYS; k++) {
    if (keys[k].sec != S_FILL || !keys[k].shapes)
      continue;
    where w = {.at = c->at[i][k], .sec = S_FILL, .key = k, .fill = i, .title = f->name};
    if (!(keys[k].shapes & mask) && is_set(c, k, i))
      return fail_key(c, &w, "not used by shape \"%s\" (allowed keys for \"%s\": %s)", shape,
                      shape, key_list(S_FILL, mask).s);
    if ((keys[k].shapes & mask) && !is_set(c, k, i))
      return fail_key(c, &w, "required for shape \"%s\", not set (allowed: %s)", shape,
                      allowed_text(&keys[k]).s);
  }
  return MPM_OK;
}

static int check_span(in_ctx *c, const mpm_config *cfg, int i, int ka, int kb, double lo,
                      double hi, int along_x)
{
  double m0 = along_x ? cfg->mesh.x0 : cfg->mesh.y0;
  double d = along_x ? cfg->mesh.dx : cfg->mesh.dy;
  double m1 = m0 + (along_x ? cfg->mesh.nx : cfg->mesh.ny) * d, tol = GEOM_TOL * d;
  if (lo >= m0 - tol && hi <= m1 + tol)
    return MPM_OK;
  where w = blame(c, cfg, i, ka, kb);
  return fail_key(c, &w, "the fill spans %s %s ... %s, outside the mesh (allowed: %s ... %s m)",
                  along_x ? "x" : "y", approx(lo).s, approx(hi).s, approx(m0).s, approx(m1).s);
}

static int check_rectangle(in_ctx *c, const mpm_config *cfg, int i)
{
  const mpm_fill_config *f = &cfg->fill[i];
  int kx0 = key_index(S_FILL, "xmin"), kx1 = key_index(S_FILL, "xmax");
  int ky0 = key_index(S_FILL, "ymin"), ky1 = key_index(S_FILL, "ymax");
  if (!(f->xmin < f->xmax)) {
    where w = blame(c, cfg, i, kx1, kx0);
    return fail_key(c, &w, "xmin = %s >= xmax = %s (allowed: xmin < xmax)", num(f->xmin).s,
                    num(f->xmax).s);
  }
  if (!(f->ymin < f->ymax)) {
    where w = blame(c, cfg, i, ky1, ky0);
    return fail_key(c, &w, "ymin = %s >= ymax = %s (allowed: ymin < ymax)", num(f->ymin).s,
                    num(f->ymax).s);
  }
  if (check_span(c, cfg, i, kx1, kx0, f->xmin, f->xmax, 1) != MPM_OK)
    return MPM_EINPUT;
  return check_span(c, cfg, i, ky1, ky0, f->ymin, f->ymax, 0);
}

static int check_disc(in_ctx *c, const mpm_config *cfg, int i)
{
  const mpm_fill_config *f = &cfg->fill[i];
  int kr = key_index(S_FILL, "radius");
  if (check_span(c, cfg, i, key_index(S_FILL, "cx"), kr, f->cx - f->radius, f->cx + f->radius,
                 1) != MPM_OK)
    return MPM_EINPUT;
  return check_span(c, cfg, i, key_index(S_FILL, "cy"), kr, f->cy - f->radius,
                    f->cy + f->radius, 0);
}

static void bounds(const double *v, int n, double *lo, double *hi)
{
  *lo = *hi = v[0];
  for (int j = 1; j < n; j++) {
    *lo = v[j] < *lo ? v[j] : *lo;
    *hi = v[j] > *hi ? v[j] : *hi;
  }
}

static int check_polygon(in_ctx *c, mpm_config *cfg, int i)
{
  mpm_fill_config *f = &cfg->fill[i];
  int kx = key_index(S_FILL, "x"), ky = key_index(S_FILL, "y");
  int nx = c->nlist[i][0], ny = c->nlist[i][1];
  where w = blame(c, cfg, i, ky, kx);
  if (nx != ny)
    return fail_key(c, &w, "x has %d values, y has %d (allowed: as many x values as y values)",
                    nx, ny);
  if (nx < 3)
    return fail_key(c, &w, "%d vertices (allowed: 3 ... %d vertices)", nx, MPM_MAX_POLY);
  f->nvert = nx;
  double area = 0, x0, x1, y0, y1;
  for (int a = 0, b = nx - 1; a < nx; b = a++)
    area += f->px[b] * f->py[a] - f->px[a] * f->py[b];  /* 2A = sum x_b y_a - x_a y_b */
  bounds(f->px, nx, &x0, &x1);
  bounds(f->py, nx, &y0, &y1);
  if (!(fabs(area) > 1e-12 * (x1 - x0) * (y1 - y0)))
    return fail_key(c, &w, "the polygon encloses no area (allowed: 3 ... %d vertices around a region)",
                    MPM_MAX_POLY);
  if (check_span(c, cfg, i, kx, ky, x0, x1, 1) != MPM_OK)
    return MPM_EINPUT;
  return check_span(c, cfg, i, ky, kx, y0, y1, 0);
}

static int check_fill(in_ctx *c, mpm_config *cfg, int i)
{
  mpm_fill_config *f = &cfg->fill[i];
  int rc = check_fill_keys(c, cfg, i);
  if (rc == MPM_OK && f->shape == MPM_FILL_RECTANGLE)
    rc = check_rectangle(c, cfg, i);
  else if (rc == MPM_OK && f->shape == MPM_FILL_DISC)
    rc = check_disc(c, cfg, i);
  else if (rc == MPM_OK)
    rc = check_polygon(c, cfg, i);
  if (rc != MPM_OK)
    return rc;
  for (int k = 0; k < NKEYS; k++)  /* defaults taken from the material */
    if ((keys[k].flags & KF_RHO_C) && !is_set(c, k, i))
      *(double *)(void *)((char *)f + keys[k].off) = cfg->material.rho_c;
  int kd = key_index(S_FILL, "density");
  if (is_set(c, kd, i) && f->density > cfg->material.rho_s) {
    where w = {.at = c->at[i][kd], .sec = S_FILL, .key = kd, .fill = i, .title = f->name};
    return fail_key(c, &w, "density = %s > material.rho_s = %s (allowed: density <= rho_s)",
                    num(f->density).s, num(cfg->material.rho_s).s);
  }
  /* The pre-stress is the weight under the full gravity, which a ramp only
   * reaches at t_ramp: at t = 0 nothing would hold it, and the fill would
   * spring apart into tension and disconnect. */
  int kl = key_index(S_FILL, "lithostatic");
  if (f->lithostatic && cfg->gravity.t_ramp > 0.0) {
    where w = {.at = c->at[i][kl], .sec = S_FILL, .key = kl, .fill = i, .title = f->name};
    return fail_key(c, &w, "lithostatic = true with gravity.t_ramp = %s s: the pre-stress "
                    "needs the full gravity from t = 0 (allowed: gravity.t_ramp = 0, or "
                    "lithostatic = false)", num(cfg->gravity.t_ramp).s);
  }
  return MPM_OK;
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
    if (find_key(S_MATERIAL, key) >= 0)
      k = find_key(S_MATERIAL, key);
  }
  where w = {.at = c->at[0][k], .sec = S_MATERIAL, .key = k, .fill = -1};
  if (named)
    return fail_at(c, &w, "%s", e.msg);
  return fail_key(c, &w, "model \"%s\": %s", show(cfg->material.model).s, e.msg);
}

/* Outlet: an extent on a non-periodic edge, inside it; closed by a wall. */
static int check_outlet(in_ctx *c, const mpm_config *cfg)
{
  const int e = cfg->outlet.edge;
  if (e == MPM_OUTLET_NONE)
    return MPM_OK;
  const int kf = key_index(S_OUTLET, "from"), kt = key_index(S_OUTLET, "to");
  const int ke = key_index(S_OUTLET, "edge"), kc = key_index(S_OUTLET, "closed");
  if (cfg->outlet.closed != MPM_BC_NOSLIP && cfg->outlet.closed != MPM_BC_FRICTIONLESS) {
    where w = blame(c, cfg, -1, kc, kc);
    return fail_key(c, &w, "\"%s\" (allowed: \"noslip\", \"frictionless\")",
                    mpm_bc_kind_name(cfg->outlet.closed));
  }
  const int kinds[] = {0, cfg->bc.left, cfg->bc.right, cfg->bc.bottom, cfg->bc.top};
  if (kinds[e] == MPM_BC_PERIODIC) {
    where w = blame(c, cfg, -1, ke, ke);
    return fail_key(c, &w, "\"%s\" is periodic (allowed: a non-periodic edge)", edge_names[e]);
  }
  const int vert = e == MPM_OUTLET_LEFT || e == MPM_OUTLET_RIGHT;
  const double d = vert ? cfg->mesh.dy : cfg->mesh.dx;
  const double m0 = vert ? cfg->mesh.y0 : cfg->mesh.x0;
  const double m1 = m0 + (vert ? cfg->mesh.ny : cfg->mesh.nx) * d, tol = GEOM_TOL * d;
  if (!(cfg->outlet.to > cfg->outlet.from)) {
    where w = blame(c, cfg, -1, kt, kf);
    return fail_key(c, &w, "to = %s <= from = %s (allowed: to > from)", num(cfg->outlet.to).s,
                    num(cfg->outlet.from).s);
  }
  if (cfg->outlet.from < m0 - tol || cfg->outlet.to > m1 + tol) {
    where w = blame(c, cfg, -1, kt, kf);
    return fail_key(c, &w, "the outlet spans %s ... %s, outside the %s edge (allowed: %s ... %s m)",
                    approx(cfg->outlet.from).s, approx(cfg->outlet.to).s, edge_names[e],
                    approx(m0).s, approx(m1).s);
  }
  return MPM_OK;
}

/* Wall polygon: as many x as y values, none or 3 ... MPM_MAX_POLY; a wall kind. */
static int check_wall(in_ctx *c, mpm_config *cfg)
{
  const int kx = key_index(S_WALL, "x"), ky = key_index(S_WALL, "y");
  const int nx = c->wall_nlist[0], ny = c->wall_nlist[1];
  where w = blame(c, cfg, -1, ky, kx);
  if (nx != ny)
    return fail_key(c, &w, "x has %d values, y has %d (allowed: as many x values as y values)",
                    nx, ny);
  if (nx > 0 && nx < 3)
    return fail_key(c, &w, "%d vertices (allowed: none, or 3 ... %d vertices)", nx,
                    MPM_MAX_POLY);
  cfg->wall.nvert = nx;
  const int kk = key_index(S_WALL, "kind");
  if (cfg->wall.kind != MPM_BC_NOSLIP && cfg->wall.kind != MPM_BC_FRICTIONLESS) {
    where wk = blame(c, cfg, -1, kk, kk);
    return fail_key(c, &wk, "\"%s\" (allowed: \"noslip\", \"frictionless\")",
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
      where w = blame(c, cfg, -1, key_index(S_REGION, pairs[i][0]), key_index(S_REGION, pairs[i][1]));
      return fail_key(c, &w, "%s = %s <= %s = %s (allowed: %s > %s)", pairs[i][0],
                      num(v[i][0]).s, pairs[i][1], num(v[i][1]).s, pairs[i][0], pairs[i][1]);
    }
  if (cfg->region.m_hi > 0.0 && !(cfg->region.m_hi > cfg->region.m_lo)) {
    where w = blame(c, cfg, -1, key_index(S_REGION, "m_hi"), key_index(S_REGION, "m_lo"));
    return fail_key(c, &w, "m_hi = %s <= m_lo = %s (allowed: m_hi > m_lo, or m_hi = 0: no fit)",
                    num(cfg->region.m_hi).s, num(cfg->region.m_lo).s);
  }
  return MPM_OK;
}

static int validate(in_ctx *c, mpm_config *cfg)
{
  if (check_required(c) != MPM_OK)
    return MPM_EINPUT;
  if (cfg->nfill == 0) {
    where w = {.sec = S_FILL, .key = -1, .fill = -1};
    return fail_at(c, &w, "no fill section (allowed: 1 ... %d sections 'fill NAME { ... }')",
                   MPM_MAX_FILLS);
  }
  if (check_mesh(c, cfg) || check_time(c, cfg) || check_gravity(c, cfg) ||
      check_material(c, cfg) || check_boundary(c, cfg) || check_outlet(c, cfg) ||
      check_wall(c, cfg) || check_region(c, cfg))
    return MPM_EINPUT;
  resolve_stop(c, cfg);
  for (int i = 0; i < cfg->nfill; i++)
    if (check_fill(c, cfg, i) != MPM_OK)
      return MPM_EINPUT;
  return check_model(c, cfg);
}

/* ----------------------------------------------------------------- public */

void mpm_input_defaults(mpm_config *cfg)
{
  memset(cfg, 0, sizeof *cfg);
  for (int k = 0; k < NKEYS; k++)
    if (keys[k].sec != S_FILL)
      store_default(cfg, &keys[k]);
  for (int k = 0; k < NKEYS; k++)  /* defaults that follow another key */
    if (keys[k].flags & KF_T0X10)
      *(double *)(void *)((char *)cfg + keys[k].off) = 10.0 * cfg->material.t0;
}

static int load(in_ctx *c, const char *path, int noverrides, mpm_config *cfg)
{
  char *buf = NULL;
  size_t len = 0;
  cfg_t *root = NULL;
  int rc = read_text(path, &buf, &len, c->err);
  if (rc == MPM_OK)
    rc = parse_text(c, buf, len, &root);
  if (rc == MPM_OK)
    rc = collect(c, root, cfg);
  if (rc == MPM_OK)
    rc = apply_overrides(c, cfg, noverrides);
  if (rc == MPM_OK)
    rc = validate(c, cfg);
  if (root)
    cfg_free(root);
  free(buf);
  return rc;
}

int mpm_input_load(const char *path, const char *const *overrides, int noverrides,
                   mpm_config *cfg, mpm_err *err)
{
  mpm_err_clear(err);
  if (!cfg || !path || noverrides < 0 || (noverrides > 0 && !overrides))
    return mpm_err_set(err, MPM_EINVAL, "mpm_input_load: invalid arguments");
  mpm_input_defaults(cfg);
  copy_text(cfg->source, sizeof cfg->source, path);
  in_ctx *c = calloc(1, sizeof *c);
  if (!c)
    return mpm_err_set(err, MPM_ENOMEM, "%s: out of memory", path);
  c->self = c;
  c->path = path;
  c->ovr = overrides;
  c->err = err;
  int rc = load(c, path, noverrides, cfg);
  free(c);
  if (rc != MPM_OK) {
    mpm_input_defaults(cfg);
    copy_text(cfg->source, sizeof cfg->source, path);
  }
  return rc;
}

/* ----------------------------------------------------------------- writer */

static void write_list(FILE *f, const double *v, int n)
{
  fputc('{', f);
  for (int i = 0; i < n; i++)
    fprintf(f, "%s%s", i ? ", " : "", num(v[i]).s);
  fputc('}', f);
}

static void write_key(FILE *f, const void *rec, const key_def *kd, int nvert)
{
  const char *p = (const char *)rec + kd->off;
  const char *name;
  fprintf(f, "  %s = ", kd->name);
  switch (kd->type) {
  case KT_INT: fprintf(f, "%d", *(const int *)(const void *)p); break;
  case KT_REAL: fputs(num(*(const double *)(const void *)p).s, f); break;
  case KT_BOOL: fputs(*(const int *)(const void *)p ? "true" : "false", f); break;
  case KT_ENUM:
    name = name_at(kd->kind, *(const int *)(const void *)p);
    fputs(quoted(name ? name : "?").s, f);
    break;
  case KT_LIST: write_list(f, (const double *)(const void *)p, nvert); break;
  default: fputs(quoted(p).s, f); break;  /* names and paths */
  }
  fputc('\n', f);
}

/* Paths can be longer than a text: written directly, escaped the same way. */
static void write_path(FILE *f, const char *s)
{
  fputc('"', f);
  for (; *s; s++) {
    if (*s == '"' || *s == '\\' || *s == '$')
      fputc('\\', f);
    fputc(*s, f);
  }
  fputc('"', f);
}

/* 1 for the gravity keys that the resolved input leaves out: gx, gy when
 * gravity came as angle and g (they are derived), angle and g otherwise. */
static int derived_key(const mpm_config *cfg, const key_def *kd)
{
  if (kd->sec != S_GRAVITY)
    return 0;
  const int polar = strcmp(kd->name, "angle") == 0 || strcmp(kd->name, "g") == 0;
  const int cart = strcmp(kd->name, "gx") == 0 || strcmp(kd->name, "gy") == 0;
  return cfg->gravity.use_angle ? cart : polar;
}

static void write_section(FILE *f, const mpm_config *cfg, int s)
{
  fprintf(f, "%s {\n", sec_names[s]);
  for (int k = 0; k < NKEYS; k++) {
    if (keys[k].sec != s || derived_key(cfg, &keys[k]))
      continue;
    if (keys[k].type == KT_PATH) {
      fprintf(f, "  %s = ", keys[k].name);
      write_path(f, (const char *)cfg + keys[k].off);
      fputc('\n', f);
    } else {
      write_key(f, cfg, &keys[k], s == S_WALL ? cfg->wall.nvert : 0);
    }
  }
  fputs("}\n", f);
}

static void write_fill(FILE *f, const mpm_fill_config *fc, int i)
{
  if (valid_title(fc->name))
    fprintf(f, "fill %s {\n", fc->name);
  else
    fprintf(f, "fill fill%d {\n", i + 1);
  int mask = fc->shape >= 0 && fc->shape <= MPM_FILL_POLYGON ? 1 << fc->shape : 0;
  int nvert = fc->nvert < 0 ? 0 : fc->nvert > MPM_MAX_POLY ? MPM_MAX_POLY : fc->nvert;
  for (int k = 0; k < NKEYS; k++)
    if (keys[k].sec == S_FILL && (!keys[k].shapes || (keys[k].shapes & mask)))
      write_key(f, fc, &keys[k], nvert);
  fputs("}\n", f);
}

int mpm_input_write(FILE *f, const mpm_config *cfg)
{
  if (!f || !cfg)
    return MPM_EINVAL;
  fputs("# granmpm input, fully resolved", f);
  if (cfg->source[0]) {
    fputs(" from ", f);
    for (const char *p = cfg->source; *p && p < cfg->source + MPM_PATH_MAX; p++)
      fputc(iscntrl((unsigned char)*p) ? '?' : *p, f);
  }
  fputc('\n', f);
  for (int s = 0; s < NSEC; s++) {
    if (s != S_FILL)
      write_section(f, cfg, s);
    else
      for (int i = 0; i < cfg->nfill && i < MPM_MAX_FILLS; i++)
        write_fill(f, &cfg->fill[i], i);
  }
  return ferror(f) ? MPM_EIO : MPM_OK;
}
