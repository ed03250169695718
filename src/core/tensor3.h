/* tensor3.h: small 3x3 tensor helpers (static inline).
 *
 * All tensors are 3x3, also in plane strain (MODEL.md section 1). Symmetric
 * tensors (stress, rate of deformation) use mpm_sym3; general ones (velocity
 * gradient L, spin W, deformation gradient F) use mpm_mat3 with
 * m[i][j] = d v_i / d x_j for L. Invariants follow MODEL.md section 1:
 * p = -tr(s)/3, s0 = s + p I, tau = sqrt(s0:s0 / 2). The general products,
 * transpose, determinant and inverse serve the deformation gradients of the
 * hyperelastic update (MODEL.md section 7). */
#ifndef MPM_CORE_TENSOR3_H
#define MPM_CORE_TENSOR3_H

#include <math.h>

typedef struct mpm_sym3 { double xx, yy, zz, xy, yz, zx; } mpm_sym3;
typedef struct mpm_mat3 { double m[3][3]; } mpm_mat3;

static inline mpm_sym3 mpm_sym3_zero(void) { return (mpm_sym3){0, 0, 0, 0, 0, 0}; }

static inline double mpm_sym3_trace(mpm_sym3 s) { return s.xx + s.yy + s.zz; }

/* p = -tr(s)/3 */
static inline double mpm_sym3_pressure(mpm_sym3 s) { return -(s.xx + s.yy + s.zz) / 3.0; }

/* s0 = s - tr(s)/3 I */
static inline mpm_sym3 mpm_sym3_dev(mpm_sym3 s)
{
  double m = (s.xx + s.yy + s.zz) / 3.0;
  return (mpm_sym3){s.xx - m, s.yy - m, s.zz - m, s.xy, s.yz, s.zx};
}

/* a : b (full double contraction of symmetric tensors) */
static inline double mpm_sym3_ddot(mpm_sym3 a, mpm_sym3 b)
{
  return a.xx * b.xx + a.yy * b.yy + a.zz * b.zz
       + 2.0 * (a.xy * b.xy + a.yz * b.yz + a.zx * b.zx);
}

/* tau = sqrt(s0:s0 / 2), the equivalent shear stress */
static inline double mpm_sym3_tau(mpm_sym3 s)
{
  mpm_sym3 d = mpm_sym3_dev(s);
  return sqrt(0.5 * mpm_sym3_ddot(d, d));
}

static inline mpm_sym3 mpm_sym3_scale(mpm_sym3 s, double a)
{
  return (mpm_sym3){a * s.xx, a * s.yy, a * s.zz, a * s.xy, a * s.yz, a * s.zx};
}

static inline mpm_sym3 mpm_sym3_add(mpm_sym3 a, mpm_sym3 b)
{
  return (mpm_sym3){a.xx + b.xx, a.yy + b.yy, a.zz + b.zz, a.xy + b.xy, a.yz + b.yz, a.zx + b.zx};
}

/* a + c b */
static inline mpm_sym3 mpm_sym3_axpy(mpm_sym3 a, double c, mpm_sym3 b)
{
  return (mpm_sym3){a.xx + c * b.xx, a.yy + c * b.yy, a.zz + c * b.zz,
                    a.xy + c * b.xy, a.yz + c * b.yz, a.zx + c * b.zx};
}

/* s + a I */
static inline mpm_sym3 mpm_sym3_add_iso(mpm_sym3 s, double a)
{
  return (mpm_sym3){s.xx + a, s.yy + a, s.zz + a, s.xy, s.yz, s.zx};
}

/* D = sym(L) */
static inline mpm_sym3 mpm_mat3_sym(const mpm_mat3 *L)
{
  return (mpm_sym3){L->m[0][0], L->m[1][1], L->m[2][2],
                    0.5 * (L->m[0][1] + L->m[1][0]),
                    0.5 * (L->m[1][2] + L->m[2][1]),
                    0.5 * (L->m[2][0] + L->m[0][2])};
}

/* W = skw(L): W_ij = (L_ij - L_ji)/2, from its independent components
 * a = W_xy, b = W_yz, c = W_zx (written out: no loop in the hot loops) */
static inline mpm_mat3 mpm_mat3_skw(const mpm_mat3 *L)
{
  const double a = 0.5 * (L->m[0][1] - L->m[1][0]);
  const double b = 0.5 * (L->m[1][2] - L->m[2][1]);
  const double c = 0.5 * (L->m[2][0] - L->m[0][2]);
  return (mpm_mat3){{{0.0, a, -c}, {-a, 0.0, b}, {c, -b, 0.0}}};
}

static inline double mpm_mat3_trace(const mpm_mat3 *L) { return L->m[0][0] + L->m[1][1] + L->m[2][2]; }

/* Full matrix view of a symmetric tensor. */
static inline mpm_mat3 mpm_sym3_full(mpm_sym3 s)
{
  return (mpm_mat3){{{s.xx, s.xy, s.zx}, {s.xy, s.yy, s.yz}, {s.zx, s.yz, s.zz}}};
}

/* Jaumann spin term W s - s W for skew W and symmetric s. Since W^T = -W,
 * W s - s W = P + P^T with P = W s; written out in the independent
 * components a = W_xy, b = W_yz, c = W_zx of W (W_yx = -a, ...), so only
 * those entries of W are read. Plane strain has b = c = 0. */
static inline mpm_sym3 mpm_sym3_spin(const mpm_mat3 *W, mpm_sym3 s)
{
  const double a = W->m[0][1], b = W->m[1][2], c = W->m[2][0];
  return (mpm_sym3){2.0 * (a * s.xy - c * s.zx),                 /* 2 P_xx */
                    2.0 * (b * s.yz - a * s.xy),                 /* 2 P_yy */
                    2.0 * (c * s.zx - b * s.yz),                 /* 2 P_zz */
                    a * (s.yy - s.xx) + b * s.zx - c * s.yz,     /* P_xy + P_yx */
                    b * (s.zz - s.yy) + c * s.xy - a * s.zx,     /* P_yz + P_zy */
                    c * (s.xx - s.zz) + a * s.yz - b * s.xy};    /* P_zx + P_xz */
}

/* ---- general 3x3 matrices (deformation gradients, rotations) ---- */

static inline mpm_mat3 mpm_mat3_identity(void)
{
  return (mpm_mat3){{{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}}};
}

/* a b */
static inline mpm_mat3 mpm_mat3_mul(const mpm_mat3 *a, const mpm_mat3 *b)
{
  mpm_mat3 c;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      c.m[i][j] = a->m[i][0] * b->m[0][j] + a->m[i][1] * b->m[1][j] + a->m[i][2] * b->m[2][j];
  return c;
}

/* a^T */
static inline mpm_mat3 mpm_mat3_transpose(const mpm_mat3 *a)
{
  mpm_mat3 t;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      t.m[i][j] = a->m[j][i];
  return t;
}

/* det a, expanded along the first row */
static inline double mpm_mat3_det(const mpm_mat3 *a)
{
  const double (*m)[3] = a->m;
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
       - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
       + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

/* a^-1 = adj(a) / det a (non-finite entries if a is singular) */
static inline mpm_mat3 mpm_mat3_inverse(const mpm_mat3 *a)
{
  const double (*m)[3] = a->m;
  const double r = 1.0 / mpm_mat3_det(a);
  return (mpm_mat3){{{r * (m[1][1] * m[2][2] - m[1][2] * m[2][1]),
                      r * (m[0][2] * m[2][1] - m[0][1] * m[2][2]),
                      r * (m[0][1] * m[1][2] - m[0][2] * m[1][1])},
                     {r * (m[1][2] * m[2][0] - m[1][0] * m[2][2]),
                      r * (m[0][0] * m[2][2] - m[0][2] * m[2][0]),
                      r * (m[0][2] * m[1][0] - m[0][0] * m[1][2])},
                     {r * (m[1][0] * m[2][1] - m[1][1] * m[2][0]),
                      r * (m[0][1] * m[2][0] - m[0][0] * m[2][1]),
                      r * (m[0][0] * m[1][1] - m[0][1] * m[1][0])}}};
}

/* a s a^T for a general a and symmetric s (rotating a stress: Q s Q^T) */
static inline mpm_sym3 mpm_sym3_congruence(const mpm_mat3 *a, mpm_sym3 s)
{
  mpm_mat3 S = mpm_sym3_full(s), P = mpm_mat3_mul(a, &S);       /* P = a s */
  double c[3][3];
  for (int i = 0; i < 3; i++)
    for (int j = i; j < 3; j++)                                   /* (a s a^T)_ij = P_ik a_jk */
      c[i][j] = P.m[i][0] * a->m[j][0] + P.m[i][1] * a->m[j][1] + P.m[i][2] * a->m[j][2];
  return (mpm_sym3){c[0][0], c[1][1], c[2][2], c[0][1], c[1][2], c[0][2]};
}

/* Isotropic elasticity C:D = 2G D0 + K tr(D) I. */
static inline mpm_sym3 mpm_sym3_elastic(mpm_sym3 D, double G, double K)
{
  double tr = mpm_sym3_trace(D);
  return mpm_sym3_add_iso(mpm_sym3_scale(mpm_sym3_dev(D), 2.0 * G), K * tr);
}

#endif
