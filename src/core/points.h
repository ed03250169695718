/* points.h: the material-point store, structure of arrays (MODEL.md section 2).
 *
 * Every per-point field is one contiguous array of length n (capacity cap), so
 * hot loops stream through memory and vectorise. Fields are listed once in
 * MPM_POINT_FIELDS; allocation, growth, removal, output and reading a frame
 * back iterate over that list, so a new field is one line here. */
#ifndef MPM_CORE_POINTS_H
#define MPM_CORE_POINTS_H

#include <stddef.h>

#include "core/error.h"
#include "core/tensor3.h"

/* Point states (the `state` field). */
enum mpm_point_state {
  MPM_STATE_DENSE = 0,        /* rho >= rho_c and p > 0: stress carried */
  MPM_STATE_DISCONNECTED = 1  /* stress-free (rho < rho_c or p_tr <= 0) */
};

/* Every point field, once, in the order of the datasets of an output frame
 * (io/output.c; extract's default column order, which readers rely on):
 *   REAL(member, name, description, unit)  a double array of the store
 *   INT(member, name, description, unit)   an int array of the store
 *   DERIVED(key, name, description, unit)  output only, computed from the
 *                                          stored fields when a frame is written
 * name is the field's name in run.h5, run.xdmf and extract's CSV. The store
 * itself does not depend on the order. */
#define MPM_POINT_FIELDS(REAL, INT, DERIVED)                                   \
  REAL(x,       "x",      "position x", "m")                                   \
  REAL(y,       "y",      "position y", "m")                                   \
  REAL(vx,      "vx",     "velocity x", "m/s")                                 \
  REAL(vy,      "vy",     "velocity y", "m/s")                                 \
  REAL(sxx,     "sxx",    "Cauchy stress xx", "Pa")                            \
  REAL(syy,     "syy",    "Cauchy stress yy", "Pa")                            \
  REAL(szz,     "szz",    "Cauchy stress zz (out of plane)", "Pa")             \
  REAL(sxy,     "sxy",    "Cauchy stress xy", "Pa")                            \
  DERIVED(p,    "p",      "pressure -(sxx+syy+szz)/3", "Pa")                   \
  REAL(mass,    "mass",   "mass per unit thickness", "kg/m")                   \
  REAL(vol,     "volume", "true volume per unit thickness", "m^2")             \
  INT(state,    "state",  "0 dense, 1 disconnected", "-")                      \
  REAL(gdp,     "gdot_p", "equivalent plastic shear rate", "1/s")              \
  REAL(g,       "g",      "granular fluidity", "1/s")                          \
  INT(id,       "id",     "persistent point id", "-")                          \
  REAL(r1x,     "r1x",    "extent half-vector r1, x", "m")                     \
  REAL(r1y,     "r1y",    "extent half-vector r1, y", "m")                     \
  REAL(r2x,     "r2x",    "extent half-vector r2, x", "m")                     \
  REAL(r2y,     "r2y",    "extent half-vector r2, y", "m")

/* Stored fields that are state of the scheme, not results: kept in the
 * store and in checkpoints, not written to frames. X(member, name,
 * description, unit) as REAL above. */
#define MPM_POINT_STATE_FIELDS(X)                                              \
  X(cxx,        "cxx",    "affine velocity matrix C, xx (time.transfer = apic)", "1/s") \
  X(cxy,        "cxy",    "affine velocity matrix C, xy", "1/s")                \
  X(cyx,        "cyx",    "affine velocity matrix C, yx", "1/s")                \
  X(cyy,        "cyy",    "affine velocity matrix C, yy", "1/s")

/* The stored fields of one kind: X(member, name, description, unit). */
#define MPM_POINT_SKIP_(f, nm, d, u)
#define MPM_POINT_REAL_FIELDS(X) MPM_POINT_FIELDS(X, MPM_POINT_SKIP_, MPM_POINT_SKIP_) \
  MPM_POINT_STATE_FIELDS(X)
#define MPM_POINT_INT_FIELDS(X) MPM_POINT_FIELDS(MPM_POINT_SKIP_, X, MPM_POINT_SKIP_)

typedef struct mpm_points {
  size_t n;    /* points in use */
  size_t cap;  /* allocated length of every array */
  int next_id; /* id given to the next pushed point */
#define MPM_POINT_DECL_REAL_(f, nm, d, u) double *f;
#define MPM_POINT_DECL_INT_(f, nm, d, u) int *f;
  MPM_POINT_REAL_FIELDS(MPM_POINT_DECL_REAL_)
  MPM_POINT_INT_FIELDS(MPM_POINT_DECL_INT_)
#undef MPM_POINT_DECL_REAL_
#undef MPM_POINT_DECL_INT_
} mpm_points;

/* Stress of point i (plane strain: yz = zx = 0). */
static inline mpm_sym3 mpm_points_stress(const mpm_points *pts, size_t i)
{
  return (mpm_sym3){pts->sxx[i], pts->syy[i], pts->szz[i], pts->sxy[i], 0.0, 0.0};
}

/* Pressure of point i: p = -(sxx + syy + szz) / 3, compression positive. */
static inline double mpm_points_pressure(const mpm_points *pts, size_t i)
{
  return mpm_sym3_pressure(mpm_points_stress(pts, i));
}

/* Allocate an empty store with room for cap points (cap may be 0). */
mpm_points *mpm_points_alloc(size_t cap);
void mpm_points_free(mpm_points *pts);  /* accepts NULL */

/* Make room for at least cap points; contents kept. */
int mpm_points_reserve(mpm_points *pts, size_t cap);

/* Append one point with every field zero except the ones set by the caller
 * afterwards; returns its index in *idx. The id is a running count that removal never reuses. */
int mpm_points_push(mpm_points *pts, size_t *idx);

/* dst becomes a copy of src (points, order, next_id); dst grows if needed. */
int mpm_points_copy(mpm_points *dst, const mpm_points *src);

/* Remove every point i with keep[i] == 0, preserving the order of the rest. */
void mpm_points_compact(mpm_points *pts, const unsigned char *keep);

/* Reorder the points: point k becomes the former point order[k], for order
 * a permutation of 0 .. n-1. scratch: allocated room for n doubles. */
void mpm_points_permute(mpm_points *pts, const int *order, void *scratch);

#endif
