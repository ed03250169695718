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
 *   REAL(member, name, description, unit, dim)  a double array of the store
 *   INT(member, name, description, unit, dim)   an int array of the store
 *   DERIVED(key, name, description, unit, dim)  output only, computed from the
 *                                          stored fields when a frame is written
 * name is the field's name in run.h5, run.xdmf and extract's CSV. dim is the
 * smallest store dimension that has the field: 2, every store; 3, only a 3D
 * store (the third coordinate, velocity and extent components, the third
 * extent vector and the shear stresses that plane strain makes zero). A 2D
 * store leaves a dim-3 array NULL and never touches it: it is allocated,
 * grown, pushed, compacted, reordered, checkpointed and written only when
 * the store is 3D (mpm_points_has). Units are those of a 2D store (per unit
 * thickness); a 3D frame writes mass and volume in kg and m^3. The store
 * itself does not depend on the order. */
#define MPM_POINT_FIELDS(REAL, INT, DERIVED)                                   \
  REAL(x,       "x",      "position x", "m", 2)                                \
  REAL(y,       "y",      "position y", "m", 2)                                \
  REAL(z,       "z",      "position z", "m", 3)                                \
  REAL(vx,      "vx",     "velocity x", "m/s", 2)                              \
  REAL(vy,      "vy",     "velocity y", "m/s", 2)                              \
  REAL(vz,      "vz",     "velocity z", "m/s", 3)                              \
  REAL(sxx,     "sxx",    "Cauchy stress xx", "Pa", 2)                         \
  REAL(syy,     "syy",    "Cauchy stress yy", "Pa", 2)                         \
  REAL(szz,     "szz",    "Cauchy stress zz (out of plane)", "Pa", 2)          \
  REAL(sxy,     "sxy",    "Cauchy stress xy", "Pa", 2)                         \
  REAL(syz,     "syz",    "Cauchy stress yz", "Pa", 3)                         \
  REAL(szx,     "szx",    "Cauchy stress zx", "Pa", 3)                         \
  DERIVED(p,    "p",      "pressure -(sxx+syy+szz)/3", "Pa", 2)                \
  REAL(mass,    "mass",   "mass per unit thickness", "kg/m", 2)                \
  REAL(vol,     "volume", "true volume per unit thickness", "m^2", 2)          \
  INT(state,    "state",  "0 dense, 1 disconnected", "-", 2)                   \
  REAL(gdp,     "gdot_p", "equivalent plastic shear rate", "1/s", 2)           \
  REAL(g,       "g",      "granular fluidity", "1/s", 2)                       \
  INT(id,       "id",     "persistent point id", "-", 2)                       \
  REAL(r1x,     "r1x",    "extent half-vector r1, x", "m", 2)                  \
  REAL(r1y,     "r1y",    "extent half-vector r1, y", "m", 2)                  \
  REAL(r1z,     "r1z",    "extent half-vector r1, z", "m", 3)                  \
  REAL(r2x,     "r2x",    "extent half-vector r2, x", "m", 2)                  \
  REAL(r2y,     "r2y",    "extent half-vector r2, y", "m", 2)                  \
  REAL(r2z,     "r2z",    "extent half-vector r2, z", "m", 3)                  \
  REAL(r3x,     "r3x",    "extent half-vector r3, x", "m", 3)                  \
  REAL(r3y,     "r3y",    "extent half-vector r3, y", "m", 3)                  \
  REAL(r3z,     "r3z",    "extent half-vector r3, z", "m", 3)

/* Stored fields that are state of the scheme, not results: kept in the
 * store and in checkpoints, not written to frames. X(member, name,
 * description, unit, dim) as REAL above. */
#define MPM_POINT_STATE_FIELDS(X)                                              \
  X(cxx,        "cxx",    "affine velocity matrix C, xx (time.transfer = apic)", "1/s", 2) \
  X(cxy,        "cxy",    "affine velocity matrix C, xy", "1/s", 2)             \
  X(cyx,        "cyx",    "affine velocity matrix C, yx", "1/s", 2)             \
  X(cyy,        "cyy",    "affine velocity matrix C, yy", "1/s", 2)             \
  X(cxz,        "cxz",    "affine velocity matrix C, xz", "1/s", 3)             \
  X(cyz,        "cyz",    "affine velocity matrix C, yz", "1/s", 3)             \
  X(czx,        "czx",    "affine velocity matrix C, zx", "1/s", 3)             \
  X(czy,        "czy",    "affine velocity matrix C, zy", "1/s", 3)             \
  X(czz,        "czz",    "affine velocity matrix C, zz", "1/s", 3)             \
  X(fxx,        "fxx",    "deformation gradient F (material.model = ngf_hyper), xx", "-", 3) \
  X(fxy,        "fxy",    "F, xy", "-", 3)                                     \
  X(fxz,        "fxz",    "F, xz", "-", 3)                                     \
  X(fyx,        "fyx",    "F, yx", "-", 3)                                     \
  X(fyy,        "fyy",    "F, yy", "-", 3)                                     \
  X(fyz,        "fyz",    "F, yz", "-", 3)                                     \
  X(fzx,        "fzx",    "F, zx", "-", 3)                                     \
  X(fzy,        "fzy",    "F, zy", "-", 3)                                     \
  X(fzz,        "fzz",    "F, zz", "-", 3)                                     \
  X(fpxx,       "fpxx",   "plastic deformation gradient Fp (ngf_hyper), xx", "-", 3) \
  X(fpxy,       "fpxy",   "Fp, xy", "-", 3)                                    \
  X(fpxz,       "fpxz",   "Fp, xz", "-", 3)                                    \
  X(fpyx,       "fpyx",   "Fp, yx", "-", 3)                                    \
  X(fpyy,       "fpyy",   "Fp, yy", "-", 3)                                    \
  X(fpyz,       "fpyz",   "Fp, yz", "-", 3)                                    \
  X(fpzx,       "fpzx",   "Fp, zx", "-", 3)                                    \
  X(fpzy,       "fpzy",   "Fp, zy", "-", 3)                                    \
  X(fpzz,       "fpzz",   "Fp, zz", "-", 3)

/* The stored fields of one kind: X(member, name, description, unit, dim). */
#define MPM_POINT_SKIP_(f, nm, d, u, dim)
#define MPM_POINT_REAL_FIELDS(X) MPM_POINT_FIELDS(X, MPM_POINT_SKIP_, MPM_POINT_SKIP_) \
  MPM_POINT_STATE_FIELDS(X)
#define MPM_POINT_INT_FIELDS(X) MPM_POINT_FIELDS(MPM_POINT_SKIP_, X, MPM_POINT_SKIP_)

/* 1 when store pts has the fields of dimension D (the last column above):
 * a constant 1 for D = 2, so the 2D fields' code carries no test. */
#define mpm_points_has(pts, D) ((D) == 2 || (pts)->dim >= (D))

typedef struct mpm_points {
  size_t n;    /* points in use */
  size_t cap;  /* allocated length of every array */
  int next_id; /* id given to the next pushed point */
  int dim;     /* 2 (plane strain) or 3: which fields are allocated */
#define MPM_POINT_DECL_REAL_(f, nm, d, u, dim) double *f;
#define MPM_POINT_DECL_INT_(f, nm, d, u, dim) int *f;
  MPM_POINT_REAL_FIELDS(MPM_POINT_DECL_REAL_)
  MPM_POINT_INT_FIELDS(MPM_POINT_DECL_INT_)
#undef MPM_POINT_DECL_REAL_
#undef MPM_POINT_DECL_INT_
} mpm_points;

/* Stress of point i: the full tensor of a 3D store; plane strain has
 * yz = zx = 0. */
static inline mpm_sym3 mpm_points_stress(const mpm_points *pts, size_t i)
{
  mpm_sym3 s = {pts->sxx[i], pts->syy[i], pts->szz[i], pts->sxy[i], 0.0, 0.0};
  if (pts->dim == 3) {
    s.yz = pts->syz[i];
    s.zx = pts->szx[i];
  }
  return s;
}

/* Pressure of point i: p = -(sxx + syy + szz) / 3, compression positive. */
static inline double mpm_points_pressure(const mpm_points *pts, size_t i)
{
  return mpm_sym3_pressure(mpm_points_stress(pts, i));
}

/* Allocate an empty 2D store with room for cap points (cap may be 0). */
mpm_points *mpm_points_alloc(size_t cap);

/* The same for a store of dimension dim (2 or 3; NULL for another). */
mpm_points *mpm_points_alloc_dim(size_t cap, int dim);

/* Change the dimension of a store (2 or 3): the 3D fields are allocated
 * (zero) or freed; the other fields and the points are kept. */
int mpm_points_set_dim(mpm_points *pts, int dim);
void mpm_points_free(mpm_points *pts);  /* accepts NULL */

/* Make room for at least cap points; contents kept. */
int mpm_points_reserve(mpm_points *pts, size_t cap);

/* Append one point with every field zero except the ones set by the caller
 * afterwards; returns its index in *idx. The id is a running count that removal never reuses. */
int mpm_points_push(mpm_points *pts, size_t *idx);

/* dst becomes a copy of src (points, order, next_id, dimension); dst grows
 * if needed. */
int mpm_points_copy(mpm_points *dst, const mpm_points *src);

/* Remove every point i with keep[i] == 0, preserving the order of the rest. */
void mpm_points_compact(mpm_points *pts, const unsigned char *keep);

/* Reorder the points: point k becomes the former point order[k], for order
 * a permutation of 0 .. n-1. scratch: allocated room for n doubles. */
void mpm_points_permute(mpm_points *pts, const int *order, void *scratch);

#endif
