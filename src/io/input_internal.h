/* input_internal.h: what the files of the input reader share (not part of
 * the io.h API): input files (libconfuse) -> mpm_config: defaults, typed and
 * range-checked values, --set overrides, cross-field checks, and the writer
 * of the fully resolved input (docs/input-reference.md).
 *
 * One table, mpm_io_in_keys[], lists every key with its section, type, default,
 * allowed range, unit and offset into mpm_config (or, for the keys of a
 * titled section, into its record: mpm_fill_config, mpm_body_config). Defaults, parsing,
 * overrides, the required-key check and the writer are all driven by it;
 * tests/test_input.c checks the reference page against it.
 *
 * A titled section ("fill NAME { ... }", "body NAME { ... }") is repeated,
 * each item a record of an array of mpm_config; a second table,
 * mpm_io_in_titled[], gives each titled section its array, count and
 * maximum, so that one mechanism parses, overrides, checks and writes them
 * all. Keys set in item i are recorded in row i of in_ctx.at (row 0 also
 * holds the plain sections').
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
 * file is rejected as an unknown key. Only the first error is kept.
 *
 * The files (a load runs parse, override, check; keys and text serve all):
 *     input.c           the public entry points: defaults, load
 *     input_keys.c      the key table, sections and the names each key allows
 *     input_text.c      message pieces and the recording of the first error
 *     input_parse.c     reading the file, libconfuse glue, collecting values
 *     input_value.c     typed values: parse, range-check and store one key
 *     input_override.c  --set section.key=value
 *     input_check.c     cross-field checks, derived defaults
 *     input_fill.c      the checks of a fill
 *     input_body.c      the checks of a rigid body
 *     input_shared.c    what the checks share: where a key was set, which of two
 *                       keys to name, the keys of an item's form, polygons
 *     input_write.c     the fully resolved input, as an input file
 * Functions and tables shared between them are declared here and named mpm_io_in_*;
 * everything else in them is static. The mpm_io_in_* names are hidden: they link the
 * parts together but are not exported from libgranmpm. */
#ifndef MPM_IO_INPUT_INTERNAL_H
#define MPM_IO_INPUT_INTERNAL_H

#include <confuse.h>
#include <stdarg.h>
#include <stddef.h>

#include "io/io.h"

#pragma GCC visibility push(hidden)

#define SHOW_MAX 60  /* user text longer than this is cut in messages */

/* ------------------------------------------------------------ the key table */

enum section {
  S_MESH, S_TIME, S_GRAVITY, S_MATERIAL, S_BOUNDARY, S_FILL, S_BODY, S_STOP, S_OUTPUT,
  S_OUTLET, S_WALL, S_REMOVE, S_REGION, S_ABSORB, NSEC
};

enum key_type {
  KT_INT,   /* int */
  KT_REAL,  /* double */
  KT_BOOL,  /* int 0/1, written true/false */
  KT_NAME,  /* char[MPM_NAME_MAX], one of a name table */
  KT_ENUM,  /* int, the index of a name in a name table */
  KT_PATH,  /* char[MPM_PATH_MAX] */
  KT_LIST   /* double[MPM_MAX_POLY]: polygon coordinates, a body's times and velocities */
};

enum name_kind {
  NK_NONE, NK_TOPOLOGY, NK_DIAGONAL, NK_SHAPE, NK_MODEL, NK_BC, NK_FILL_SHAPE, NK_NGF_FORM,
  NK_NGF_P_SAMPLE, NK_NGF_G_AVERAGE, NK_DENSITY, NK_EDGE, NK_DILATATION, NK_TRANSFER, NK_DIFFUSION,
  NK_G_WALL, NK_G_SAMPLE, NK_G_MASS, NK_WALL_ACC, NK_OUTLET_SHAPE,
  NK_OUTLET_ENDS, NK_FILL_AXIS, NK_BODY_SHAPE, NK_BODY_SIDE, NK_BODY_CONTACT
};

enum key_flag {
  KF_REQUIRED = 1,  /* no default (fill keys: required by the forms that use it) */
  KF_LO_OPEN = 2,   /* value > lo rather than >= lo */
  KF_HI_OPEN = 4,   /* value < hi rather than <= hi */
  KF_RHO_C = 8,     /* default: material.rho_c */
  KF_T0X10 = 16,    /* default: 10 material.t0 */
  KF_ZERO_OFF = 32, /* 0 ("off", "from another key") or a value in the range */
  KF_3D = 64,       /* a key of 3D runs (mesh.nz > 0): refused in a plane run, and
                       left out of its resolved input (mesh.nz itself too when 0) */
  KF_RISING = 128   /* a list of strictly increasing values */
};

/* The titled sections, in the order of enum section. */
enum titled { T_FILL, T_BODY, NTITLED };

typedef struct titled_def {
  unsigned char sec;  /* enum section */
  int max;            /* items allowed */
  size_t count_off;   /* int: the number of items, in mpm_config */
  size_t array_off;   /* the first record, in mpm_config */
  size_t size;        /* one record */
  size_t name_off;    /* char[MPM_NAME_MAX]: the title, in the record */
} titled_def;

/* The rows of in_ctx.at: the items of the largest titled section. */
#define MAX_ITEMS (MPM_MAX_FILLS > MPM_MAX_BODIES ? MPM_MAX_FILLS : MPM_MAX_BODIES)

extern const titled_def mpm_io_in_titled[NTITLED];

/* The forms of fill that use a key (0: every form): in a plane run the
 * shape (rectangle, disc, polygon); in a 3D run the shape and its extent: a
 * box, a prism along z, or a cylinder along x, y or z (a disc and its
 * fill.axis). A form is one bit: mpm_io_in_fill_form. */
#define SH_RECT (1 << MPM_FILL_RECTANGLE)
#define SH_DISC (1 << MPM_FILL_DISC)
#define SH_POLY (1 << MPM_FILL_POLYGON)
#define SH_BOX (SH_POLY << 1)
#define SH_PRISM (SH_POLY << 2)
#define SH_CYL_X (SH_POLY << 3)
#define SH_CYL_Y (SH_POLY << 4)
#define SH_CYL_Z (SH_POLY << 5)
#define SH_CYL (SH_CYL_X | SH_CYL_Y | SH_CYL_Z)

/* The shapes of body that use a key (0: every shape), one bit each, in a
 * plane or a 3D run alike: mpm_io_in_body_form. */
#define BS_DISC (1 << MPM_BODY_DISC)
#define BS_BOX (1 << MPM_BODY_BOX)
#define BS_POLY (1 << MPM_BODY_POLYGON)

typedef struct key_def {
  const char *name;
  unsigned char sec, type, kind, flags, shapes;
  size_t off;         /* into mpm_config, or the record of a titled section */
  size_t noff;        /* a list: its int count of values, in the same record */
  double def, lo, hi; /* numeric default and range (list: range of each value) */
  const char *sdef;   /* default of names and paths */
  const char *unit;   /* "-": dimensionless */
} key_def;

/* The number of rows of mpm_io_in_keys; input_keys.c asserts that it is right. */
#define NKEYS 139

extern const key_def mpm_io_in_keys[];
extern const char *const mpm_io_in_sec_names[NSEC];

const char *mpm_io_in_name_at(int kind, int i);
int mpm_io_in_name_value(int kind, const char *s);
int mpm_io_in_find_section(const char *name);
int mpm_io_in_find_key(int sec, const char *name);
int mpm_io_in_fill_form(const mpm_fill_config *f, int dim3);
int mpm_io_in_body_form(const mpm_body_config *b);
int mpm_io_in_item_form(int t, const void *rec, int dim3);

/* Titled sections: the entry of section sec in mpm_io_in_titled (-1: a
 * plain section), the number of items, item i's record and its title. */
int mpm_io_in_titled_of(int sec);
int *mpm_io_in_count(mpm_config *cfg, int t);
int mpm_io_in_count_of(const mpm_config *cfg, int t);
void *mpm_io_in_item(mpm_config *cfg, int t, int i);
const void *mpm_io_in_item_of(const mpm_config *cfg, int t, int i);
const char *mpm_io_in_title(const mpm_config *cfg, int t, int i);

/* --------------------------------------------------------- message pieces */

/* Texts returned by value, usable inline in a printf argument list: a word
 * (one number, name or cut user text) and a text (lists, messages). */
typedef struct word { char s[SHOW_MAX + 12]; } word;
typedef struct text { char s[MPM_ERR_MSG]; } text;

void mpm_io_in_addf(text *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
word mpm_io_in_show(const char *s);
word mpm_io_in_num(double v);
word mpm_io_in_approx(double v);
word mpm_io_in_quoted(const char *s);
text mpm_io_in_name_list(int kind);
text mpm_io_in_range_text(const key_def *kd);
text mpm_io_in_allowed_text(const key_def *kd);
text mpm_io_in_key_list(int sec, int shapes);
text mpm_io_in_section_list(void);
text mpm_io_in_unknown_key_text(int sec, const char *title, const char *name);
void mpm_io_in_one_line(mpm_err *err);

/* --------------------------------------------------------- parse context */

/* Where a value came from: a file line, a --set (1 + its index), or neither
 * (the default). */
typedef struct loc {
  int line;
  int ovr;
} loc;

/* What an error is about. key < 0: a section as a whole; item < 0: no item
 * of a titled section, else its index in that section. */
typedef struct where {
  loc at;
  int sec, key, item;
  const char *title;  /* item title in the key name; NULL: "fill.key" */
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
  int item_line[NTITLED][MAX_ITEMS];
  int sec_open[NSEC];            /* opening lines found by the comment scan */
  int item_open[NTITLED][MAX_ITEMS + 1];
  int nbrace;                    /* top-level '{' seen by the comment scan */
  size_t brace_pos[MAX_BRACES];
  int brace_line[MAX_BRACES];
  loc at[MAX_ITEMS][NKEYS];      /* where each key was set: row i for item i of a
                                    titled section, row 0 also for plain sections */
  int nlist[MAX_ITEMS][NKEYS];   /* the number of values of each list key (rows as at) */
  cfg_opt_t opts[NSEC + 1][NKEYS + 2];  /* libconfuse options: sections, root last */
} in_ctx;

/* Record "LOCATION: key 'NAME': message" (fail_key) or "LOCATION: message"
 * (fail_at); only the first error is kept. Both return MPM_EINPUT. */
int mpm_io_in_fail_key(in_ctx *c, const where *w, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
int mpm_io_in_fail_at(in_ctx *c, const where *w, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
int mpm_io_in_fail_range(in_ctx *c, const where *w, const char *value);

/* ------------------------------------------------------------ typed values */

void mpm_io_in_copy_text(char *dst, size_t cap, const char *s);
int mpm_io_in_store_value(in_ctx *c, void *rec, const where *w, const char *s);
int mpm_io_in_store_list(in_ctx *c, void *rec, const where *w, const char *const *vals,
                         const loc *locs, int n);
void mpm_io_in_store_default(void *rec, const key_def *kd);

/* ------------------------------------------------- the steps of a load */

int mpm_io_in_read_text(const char *path, char **out, size_t *len, mpm_err *err);
int mpm_io_in_parse_text(in_ctx *c, char *s, size_t len, cfg_t **root);
int mpm_io_in_collect(in_ctx *c, cfg_t *root, mpm_config *cfg);
int mpm_io_in_valid_title(const char *t);
int mpm_io_in_apply_overrides(in_ctx *c, mpm_config *cfg, int n);
int mpm_io_in_validate(in_ctx *c, mpm_config *cfg);

/* -------------------------------------------------- the checks' helpers */

#define GEOM_TOL 1e-9  /* a region may overshoot the mesh by this many units */

/* The mesh along axis a (0 x, 1 y, 2 z): origin, unit size, units. */
typedef struct mesh_axis {
  double o, d;
  int n;
} mesh_axis;

mesh_axis mpm_io_in_mesh_axis(const mpm_config *cfg, int a);
int mpm_io_in_is_set(const in_ctx *c, int key, int item);
where mpm_io_in_blame(const in_ctx *c, const mpm_config *cfg, int item, int a, int b);
int mpm_io_in_check_form_keys(in_ctx *c, const mpm_config *cfg, int t, int i);
int mpm_io_in_check_vertices(in_ctx *c, const mpm_config *cfg, int i, int kx, int ky,
                             const double *px, const double *py, double box[4]);

/* The checks of item i of a titled section (called by mpm_io_in_validate). */
int mpm_io_in_check_fill(in_ctx *c, mpm_config *cfg, int i);
int mpm_io_in_check_body(in_ctx *c, mpm_config *cfg, int i);

#pragma GCC visibility pop

#endif
