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
 *   REAL(member, name, description, unit, kind)  a double array of the store
 *   INT(member, name, description, unit, kind)   an int array of the store
 *   DERIVED(key, name, description, unit, kind)  output only, computed from the
 *                                          stored fields when a frame is written
 * name is the field's name in run.h5, run.xdmf and extract's CSV. kind says
 * which stores have the field: MPM_POINT_EVERY (2), every store;
 * MPM_POINT_3D (3), a 3D store only (the third coordinate, velocity and
 * extent components, the third extent vector and the shear stresses that
 * plane strain makes zero); MPM_POINT_DEFGRAD, a store of a model whose
 * points carry their deformation gradients (material.h). A store without a
 * kind leaves its arrays NULL and never touches them: they are allocated,
 * grown, pushed, compacted, reordered, checkpointed and written only when
 * the store has them (mpm_points_has). Units are those of a 2D store (per
 * unit thickness); a 3D frame writes mass and volume in kg and m^3. The
 * store itself does not depend on the order.
 *
 * The vectors and tensors are listed by component in groups, so that the
 * store also holds them as arrays indexed by component (pos[d], vel[d],
 * sig[k] in the order of mpm_sym3, ext[k][d] = component d of the extent
 * half-vector r_{k+1}, aff[i][j] = C_ij, F[i][j], Fp[i][j]): code over the
 * axes is written once for any dimension. */
enum { MPM_POINT_EVERY = 2, MPM_POINT_3D = 3, MPM_POINT_DEFGRAD = 4 };

#define MPM_POINT_POS(X)                                                       \
  X(x,       "x",      "position x", "m", MPM_POINT_EVERY)                     \
  X(y,       "y",      "position y", "m", MPM_POINT_EVERY)                     \
  X(z,       "z",      "position z", "m", MPM_POINT_3D)
#define MPM_POINT_VEL(X)                                                       \
  X(vx,      "vx",     "velocity x", "m/s", MPM_POINT_EVERY)                   \
  X(vy,      "vy",     "velocity y", "m/s", MPM_POINT_EVERY)                   \
  X(vz,      "vz",     "velocity z", "m/s", MPM_POINT_3D)
#define MPM_POINT_STRESS(X)                                                    \
  X(sxx,     "sxx",    "Cauchy stress xx", "Pa", MPM_POINT_EVERY)              \
  X(syy,     "syy",    "Cauchy stress yy", "Pa", MPM_POINT_EVERY)              \
  X(szz,     "szz",    "Cauchy stress zz (out of plane)", "Pa", MPM_POINT_EVERY) \
  X(sxy,     "sxy",    "Cauchy stress xy", "Pa", MPM_POINT_EVERY)              \
  X(syz,     "syz",    "Cauchy stress yz", "Pa", MPM_POINT_3D)                 \
  X(szx,     "szx",    "Cauchy stress zx", "Pa", MPM_POINT_3D)
#define MPM_POINT_SCALARS(REAL, INT, DERIVED)                                  \
  DERIVED(p, "p",      "pressure -(sxx+syy+szz)/3", "Pa", MPM_POINT_EVERY)     \
  REAL(mass,    "mass",   "mass per unit thickness", "kg/m", MPM_POINT_EVERY)  \
  REAL(vol,     "volume", "true volume per unit thickness", "m^2", MPM_POINT_EVERY) \
  INT(state,    "state",  "0 dense, 1 disconnected", "-", MPM_POINT_EVERY)     \
  REAL(gdp,     "gdot_p", "equivalent plastic shear rate", "1/s", MPM_POINT_EVERY) \
  REAL(g,       "g",      "granular fluidity", "1/s", MPM_POINT_EVERY)         \
  INT(id,       "id",     "persistent point id", "-", MPM_POINT_EVERY)
#define MPM_POINT_EXTENT(X)                                                    \
  X(r1x,     "r1x",    "extent half-vector r1, x", "m", MPM_POINT_EVERY)       \
  X(r1y,     "r1y",    "extent half-vector r1, y", "m", MPM_POINT_EVERY)       \
  X(r1z,     "r1z",    "extent half-vector r1, z", "m", MPM_POINT_3D)          \
  X(r2x,     "r2x",    "extent half-vector r2, x", "m", MPM_POINT_EVERY)       \
  X(r2y,     "r2y",    "extent half-vector r2, y", "m", MPM_POINT_EVERY)       \
  X(r2z,     "r2z",    "extent half-vector r2, z", "m", MPM_POINT_3D)          \
  X(r3x,     "r3x",    "extent half-vector r3, x", "m", MPM_POINT_3D)          \
  X(r3y,     "r3y",    "extent half-vector r3, y", "m", MPM_POINT_3D)          \
  X(r3z,     "r3z",    "extent half-vector r3, z", "m", MPM_POINT_3D)
#define MPM_POINT_FIELDS(REAL, INT, DERIVED)                                   \
  MPM_POINT_POS(REAL) MPM_POINT_VEL(REAL) MPM_POINT_STRESS(REAL)               \
  MPM_POINT_SCALARS(REAL, INT, DERIVED) MPM_POINT_EXTENT(REAL)

/* Stored fields that are state of the scheme or of a model, not results:
 * kept in the store and in checkpoints, not written to frames. X(member,
 * name, description, unit, kind) as REAL above. */
#define MPM_POINT_AFFINE(X)                                                    \
  X(cxx, "cxx", "affine velocity matrix C, xx (time.transfer = apic)", "1/s", MPM_POINT_EVERY) \
  X(cxy, "cxy", "affine velocity matrix C, xy", "1/s", MPM_POINT_EVERY)        \
  X(cxz, "cxz", "affine velocity matrix C, xz", "1/s", MPM_POINT_3D)           \
  X(cyx, "cyx", "affine velocity matrix C, yx", "1/s", MPM_POINT_EVERY)        \
  X(cyy, "cyy", "affine velocity matrix C, yy", "1/s", MPM_POINT_EVERY)        \
  X(cyz, "cyz", "affine velocity matrix C, yz", "1/s", MPM_POINT_3D)           \
  X(czx, "czx", "affine velocity matrix C, zx", "1/s", MPM_POINT_3D)           \
  X(czy, "czy", "affine velocity matrix C, zy", "1/s", MPM_POINT_3D)           \
  X(czz, "czz", "affine velocity matrix C, zz", "1/s", MPM_POINT_3D)
#define MPM_POINT_DEFGRAD_F(X)                                                 \
  X(fxx, "fxx", "deformation gradient F (material.model = ngf_hyper), xx", "-", MPM_POINT_DEFGRAD) \
  X(fxy, "fxy", "F, xy", "-", MPM_POINT_DEFGRAD)                               \
  X(fxz, "fxz", "F, xz", "-", MPM_POINT_DEFGRAD)                               \
  X(fyx, "fyx", "F, yx", "-", MPM_POINT_DEFGRAD)                               \
  X(fyy, "fyy", "F, yy", "-", MPM_POINT_DEFGRAD)                               \
  X(fyz, "fyz", "F, yz", "-", MPM_POINT_DEFGRAD)                               \
  X(fzx, "fzx", "F, zx", "-", MPM_POINT_DEFGRAD)                               \
  X(fzy, "fzy", "F, zy", "-", MPM_POINT_DEFGRAD)                               \
  X(fzz, "fzz", "F, zz", "-", MPM_POINT_DEFGRAD)
#define MPM_POINT_DEFGRAD_FP(X)                                                \
  X(fpxx, "fpxx", "plastic deformation gradient Fp (ngf_hyper), xx", "-", MPM_POINT_DEFGRAD) \
  X(fpxy, "fpxy", "Fp, xy", "-", MPM_POINT_DEFGRAD)                            \
  X(fpxz, "fpxz", "Fp, xz", "-", MPM_POINT_DEFGRAD)                            \
  X(fpyx, "fpyx", "Fp, yx", "-", MPM_POINT_DEFGRAD)                            \
  X(fpyy, "fpyy", "Fp, yy", "-", MPM_POINT_DEFGRAD)                            \
  X(fpyz, "fpyz", "Fp, yz", "-", MPM_POINT_DEFGRAD)                            \
  X(fpzx, "fpzx", "Fp, zx", "-", MPM_POINT_DEFGRAD)                            \
  X(fpzy, "fpzy", "Fp, zy", "-", MPM_POINT_DEFGRAD)                            \
  X(fpzz, "fpzz", "Fp, zz", "-", MPM_POINT_DEFGRAD)
#define MPM_POINT_STATE_FIELDS(X)                                              \
  MPM_POINT_AFFINE(X) MPM_POINT_DEFGRAD_F(X) MPM_POINT_DEFGRAD_FP(X)

/* The stored fields of one kind: X(member, name, description, unit, kind). */
#define MPM_POINT_SKIP_(f, nm, d, u, kind)
#define MPM_POINT_REAL_FIELDS(X) MPM_POINT_FIELDS(X, MPM_POINT_SKIP_, MPM_POINT_SKIP_) \
  MPM_POINT_STATE_FIELDS(X)
#define MPM_POINT_INT_FIELDS(X) MPM_POINT_FIELDS(MPM_POINT_SKIP_, X, MPM_POINT_SKIP_)

/* 1 when store pts has the fields of kind K (the last column above): a
 * constant 1 for MPM_POINT_EVERY, so the code of those fields carries no
 * test. */
#define mpm_points_has(pts, K)                                                 \
  ((K) == MPM_POINT_EVERY || ((K) == MPM_POINT_3D && (pts)->dim == 3) ||       \
   ((K) == MPM_POINT_DEFGRAD && (pts)->defgrad))

typedef struct mpm_points {
  size_t n;    /* points in use */
  size_t cap;  /* allocated length of every array */
  int next_id; /* id given to the next pushed point */
  int dim;     /* 2 (plane strain) or 3: which fields are allocated */
  int defgrad; /* 1: the store carries F and Fp (MPM_POINT_DEFGRAD) */
#define MPM_POINT_DECL_REAL_(f, nm, d, u, kind) double *f;
#define MPM_POINT_DECL_INT_(f, nm, d, u, kind) int *f;
  union { struct { MPM_POINT_POS(MPM_POINT_DECL_REAL_) }; double *pos[3]; };
  union { struct { MPM_POINT_VEL(MPM_POINT_DECL_REAL_) }; double *vel[3]; };
  union { struct { MPM_POINT_STRESS(MPM_POINT_DECL_REAL_) }; double *sig[6]; };
  MPM_POINT_SCALARS(MPM_POINT_DECL_REAL_, MPM_POINT_DECL_INT_, MPM_POINT_SKIP_)
  union { struct { MPM_POINT_EXTENT(MPM_POINT_DECL_REAL_) }; double *ext[3][3]; };
  union { struct { MPM_POINT_AFFINE(MPM_POINT_DECL_REAL_) }; double *aff[3][3]; };
  union { struct { MPM_POINT_DEFGRAD_F(MPM_POINT_DECL_REAL_) }; double *F[3][3]; };
  union { struct { MPM_POINT_DEFGRAD_FP(MPM_POINT_DECL_REAL_) }; double *Fp[3][3]; };
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

/* Give the store the deformation gradients F and Fp (on = 1: allocated,
 * I for every point) or take them away (0: freed); the rest is kept. */
int mpm_points_set_defgrad(mpm_points *pts, int on);
void mpm_points_free(mpm_points *pts);  /* accepts NULL */

/* Make room for at least cap points; contents kept. */
int mpm_points_reserve(mpm_points *pts, size_t cap);

/* Append one point with every field zero except the ones set by the caller
 * afterwards; returns its index in *idx. The id is a running count that removal never reuses. */
int mpm_points_push(mpm_points *pts, size_t *idx);

/* dst becomes a copy of src (points, order, next_id, dimension, the
 * deformation gradients if src has them); dst grows if needed. */
int mpm_points_copy(mpm_points *dst, const mpm_points *src);

/* Remove every point i with keep[i] == 0, preserving the order of the rest. */
void mpm_points_compact(mpm_points *pts, const unsigned char *keep);

/* Reorder the points: point k becomes the former point order[k], for order
 * a permutation of 0 .. n-1. scratch: allocated room for n doubles. */
void mpm_points_permute(mpm_points *pts, const int *order, void *scratch);

#endif
