/* points.h: the material-point store, structure of arrays (MODEL.md section 2).
 *
 * Every per-point field is one contiguous array of length n (capacity cap), so
 * hot loops stream through memory and vectorise. Fields are listed once in
 * MPM_POINT_REAL_FIELDS / MPM_POINT_INT_FIELDS; allocation, growth, removal
 * and output iterate over those lists, so a new field is one line here. */
#ifndef MPM_CORE_POINTS_H
#define MPM_CORE_POINTS_H

#include <stddef.h>

#include "core/error.h"

/* Point states (the `state` field). */
enum mpm_point_state {
  MPM_STATE_DENSE = 0,        /* rho >= rho_c and p > 0: stress carried */
  MPM_STATE_DISCONNECTED = 1  /* stress-free (rho < rho_c or p_tr <= 0) */
};

/* X(field, description, unit) */
#define MPM_POINT_REAL_FIELDS(X)                                 \
  X(x,    "position x", "m")                                     \
  X(y,    "position y", "m")                                     \
  X(vx,   "velocity x", "m/s")                                   \
  X(vy,   "velocity y", "m/s")                                   \
  X(mass, "mass per unit thickness", "kg/m")                     \
  X(vol,  "true volume per unit thickness", "m^2")               \
  X(r1x,  "extent half-vector r1, x", "m")                       \
  X(r1y,  "extent half-vector r1, y", "m")                       \
  X(r2x,  "extent half-vector r2, x", "m")                       \
  X(r2y,  "extent half-vector r2, y", "m")                       \
  X(sxx,  "Cauchy stress xx", "Pa")                              \
  X(syy,  "Cauchy stress yy", "Pa")                              \
  X(szz,  "Cauchy stress zz (out of plane)", "Pa")               \
  X(sxy,  "Cauchy stress xy", "Pa")                              \
  X(g,    "granular fluidity", "1/s")                            \
  X(gdp,  "equivalent plastic shear rate gdot_p", "1/s")

#define MPM_POINT_INT_FIELDS(X)                                  \
  X(state, "0 dense, 1 disconnected", "-")                       \
  X(id,    "persistent point id", "-")

typedef struct mpm_points {
  size_t n;    /* points in use */
  size_t cap;  /* allocated length of every array */
  int next_id; /* id given to the next pushed point */
#define MPM_POINT_DECL_REAL_(f, d, u) double *f;
#define MPM_POINT_DECL_INT_(f, d, u) int *f;
  MPM_POINT_REAL_FIELDS(MPM_POINT_DECL_REAL_)
  MPM_POINT_INT_FIELDS(MPM_POINT_DECL_INT_)
#undef MPM_POINT_DECL_REAL_
#undef MPM_POINT_DECL_INT_
} mpm_points;

/* Allocate an empty store with room for cap points (cap may be 0). */
mpm_points *mpm_points_alloc(size_t cap);
void mpm_points_free(mpm_points *pts);  /* accepts NULL */

/* Make room for at least cap points; contents kept. */
int mpm_points_reserve(mpm_points *pts, size_t cap);

/* Append one point with every field zero except the ones set by the caller
 * afterwards; returns its index in *idx. The id is a running count that removal never reuses. */
int mpm_points_push(mpm_points *pts, size_t *idx);

/* Remove every point i with keep[i] == 0, preserving the order of the rest. */
void mpm_points_compact(mpm_points *pts, const unsigned char *keep);

#endif
