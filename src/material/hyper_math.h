/* hyper_math.h: the elementary pieces of hyper.c's point update, written
 * to be inlined into its loops over a block's points so that they
 * vectorise: ln(1 + x) and exp(x) without branches or library calls, and
 * the cyclic Jacobi rotations of one symmetric 3x3 (hyper.c says why this
 * route and how many sweeps). Included by hyper.c only. */
#ifndef MPM_MATERIAL_HYPER_MATH_H
#define MPM_MATERIAL_HYPER_MATH_H

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

/* Written to be inlined where it is used: into the loops over a block's
 * points, which then vectorise, and into the point functions; or kept as
 * one function that every path calls (the eigen pass). HYPER_IVDEP: the
 * iterations of the loop that follows are independent (the points of a
 * block, read and written through arrays the compiler cannot tell apart). */
#if defined(__GNUC__)
#define HYPER_INLINE static inline __attribute__((always_inline))
#define HYPER_NOINLINE static __attribute__((noinline))
#else
#define HYPER_INLINE static inline
#define HYPER_NOINLINE static
#endif
#if defined(__GNUC__) && !defined(__clang__)
#define HYPER_IVDEP _Pragma("GCC ivdep")
#else
#define HYPER_IVDEP
#endif

/* ---- ln(1 + x) and exp(x) that vectorise ------------------------------------
 * Each reduces its argument by a power of two, taken and put back on the
 * bits, and sums a series on the reduced range whose coefficients are exact
 * fractions (below), without branches or library calls, so a loop of
 * points calls no library function and vectorises. tests/test_hyper.c
 * measures both against long double over dense sweeps (t_log1p_exp). */

HYPER_INLINE uint64_t bits_of(double x)
{
  uint64_t b;
  memcpy(&b, &x, sizeof b);
  return b;
}

HYPER_INLINE double of_bits(uint64_t b)
{
  double x;
  memcpy(&x, &b, sizeof x);
  return x;
}

/* ln 2 = LN2_HI + LN2_LO: LN2_HI is ln 2 rounded to a 29-bit significand,
 * so k LN2_HI is exact for the |k| < 2^11 of a double's exponents; LN2_LO
 * the rest, rounded (together within 1.4e-27 of ln 2). */
#define LN2_HI 0x1.62e42ffp-1
#define LN2_LO -0x1.718432a1b0e26p-35

/* ln(1 + x): u = 1 + x rounded and its exact error c (1 + x = u + c, by
 * Fast2Sum); u = 2^k m with m in [sqrt(2)/2, sqrt(2)), f = m - 1 (exact);
 * ln(1 + x) = k ln 2 + ln(1 + f) + c/u. With s = f / (2 + f) (|s| <= 0.172),
 * ln(1 + f) = 2 atanh(s) = 2s + s R, R = sum_j 2 s^2j / (2j + 1), and since
 * 2s = f - s f = f - f^2/2 + s f^2/2, ln(1 + f) = f - f^2/2 + s (f^2/2 + R),
 * the small terms added to f last. R to j = 10: the next term is below
 * 2 (0.172)^22 / 23 < 2^-58 of f. x = -1: -inf; x < -1 or NaN: NaN; +inf:
 * +inf. */
HYPER_INLINE double hyper_log1p(double x)
{
  const double u = 1.0 + x;
  const double c = x < 1.0 ? x - (u - 1.0) : 1.0 - (u - x);       /* 1 + x - u, exactly */
  /* m: the mantissa of u scaled into [sqrt(2)/2, sqrt(2)) (0x3fe6a09e:
   * the high word of sqrt(2)/2), k its exponent */
  const uint64_t b = bits_of(u) + ((uint64_t)(0x3ff00000 - 0x3fe6a09e) << 32);
  const double k = of_bits(0x4330000000000000u | b >> 52) - (0x1p52 + 1023.0);   /* exponent */
  const double f = of_bits((b & 0x000fffffffffffffu) + ((uint64_t)0x3fe6a09e << 32)) - 1.0;
  const double s = f / (2.0 + f), z = s * s;
  double R = 2.0 / 21;
  for (int j = 9; j >= 1; j--)                                     /* Horner in z */
    R = 2.0 / (2 * j + 1) + z * R;
  R *= z;
  const double hfsq = 0.5 * f * f;
  const double r = s * (hfsq + R) + (k * LN2_LO + c / u) - hfsq + f + k * LN2_HI;
  return u > 0.0 && u < INFINITY ? r : u == 0.0 ? -INFINITY : u > 0.0 ? u : NAN;
}

/* exp(x): k = round(x / ln 2) (by adding and taking off 1.5 2^52),
 * r = x - k ln 2 = hi - lo (hi exact), |r| <= 0.347; with
 * c = r - (r coth(r/2) - 2), exp(r) = 1 + r + r c / (2 - c), the form that
 * keeps the rounding of the series small; r coth(r/2) - 2 by its Taylor
 * series, sum_n 2 B_2n r^2n / (2n)! over n = 1 .. 6 (B_2n the Bernoulli
 * numbers: 1/6, -1/360, 1/15120, -1/604800, 1/23950080, -691/653837184000;
 * the next term moves exp(r) by less than 2^-58 of it); times 2^k = 2^k1 2^k2 (k1 = floor(k/2):
 * each factor normal, one rounding for a subnormal result). x > 710: +inf,
 * x < -746: 0, NaN: NaN. */
HYPER_INLINE double hyper_exp(double x)
{
  const double big = 0x1.8p52;
  const double xc = x > 710.0 ? 710.0 : x < -746.0 ? -746.0 : x;   /* beyond: inf, 0 */
  const double k = (xc * 0x1.71547652b82fep0 + big) - big;        /* round(x / ln 2) */
  const double hi = xc - k * LN2_HI, lo = k * LN2_LO, r = hi - lo, rr = r * r;
  const double T = rr * (1.0 / 6 + rr * (-1.0 / 360 + rr * (1.0 / 15120 + rr *
                   (-1.0 / 604800 + rr * (1.0 / 23950080 + rr * (-691.0 / 653837184000.0))))));
  const double c = r - T;
  const double y = 1.0 - ((lo - (r * c) / (2.0 - c)) - hi);        /* exp(r) */
  const double k1 = floor(0.5 * k), k2 = k - k1;
  const double s1 = of_bits((bits_of(k1 + big) + 1023) << 52);     /* 2^k1 */
  const double s2 = of_bits((bits_of(k2 + big) + 1023) << 52);     /* 2^k2 */
  return y * s1 * s2;
}

/* ---- cyclic Jacobi on one symmetric 3x3 ------------------------------------
 * The matrix is held as a[6] in the order of mpm_sym3 (xx yy zz xy yz zx),
 * the accumulated rotation as v[9] row-major (v[3 k + j] = V_kj, the
 * columns the eigenvectors). */

/* a_pq is negligible next to a_pp and a_qq when it is below eps/2 of their
 * geometric mean: it then moves no eigenvalue by more than round-off
 * relative to itself, so graded and near-zero matrices keep their relative
 * accuracy. False for a NaN. */
HYPER_INLINE int jacobi_negligible(double app, double aqq, double apq)
{
  return fabs(apq) <= 0.5 * DBL_EPSILON * sqrt(fabs(app)) * sqrt(fabs(aqq));
}

/* One Jacobi rotation in the plane (p, q), r the third index, that zeroes
 * a_pq, accumulated into the columns p, q of v: a <- J^T a J, v <- v J with
 * J_pp = J_qq = c, J_pq = -J_qp = s, t = s/c the smaller root of
 * t^2 + 2 theta t - 1 = 0, theta = (a_qq - a_pp) / (2 a_pq).
 * sqrt(1 + theta^2) is |theta| itself in double above 1e150 (where theta^2
 * would overflow), so no hypot is needed. A zero a_pq is the rotation by
 * t = 0 (c = 1, s = 0), which changes nothing, exactly: theta is infinite
 * (|t| = 1/inf) or 0/0 (|t| NaN, taken as 0), so the zeros of a
 * plane-strain matrix stay zeros.
 * Branch-free, so a loop of points vectorises. identity: v = I on entry and
 * (p, q) = (0, 1), v J written out (the update of the general case for
 * those entries, without its products by 0 and 1). */
HYPER_INLINE void jacobi_rotate(double *app, double *aqq, double *apq, double *arp, double *arq,
                                double *v0p, double *v0q, double *v1p, double *v1q, double *v2p,
                                double *v2q, int identity)
{
  const double a = *apq, dp = *app, dq = *aqq;
  const double theta = (dq - dp) / (2.0 * a), at = fabs(theta);
  const double root = at < 1e150 ? sqrt(1.0 + at * at) : at;       /* sqrt(1 + theta^2) */
  const double r = 1.0 / (at + root);                              /* |t|; a = 0: 0 or NaN */
  const double t = copysign(r <= 1.0 ? r : 0.0, theta);
  const double c = 1.0 / sqrt(1.0 + t * t), s = t * c;
  const double h = s / (1.0 + c);                                  /* tan(angle/2) */
  *app = dp - t * a;                                               /* a_pp - t a_pq */
  *aqq = dq + t * a;                                               /* a_qq + t a_pq */
  *apq = 0.0;
  const double xp = *arp, xq = *arq;
  *arp = xp - s * (xq + h * xp);                                   /* c a_rp - s a_rq */
  *arq = xq + s * (xp - h * xq);                                   /* s a_rp + c a_rq */
  if (identity) {
    *v0p = *v1q = 1.0 - s * h;                                     /* c */
    *v0q = s;
    *v1p = -s;
    return;
  }
  double *const vp[3] = {v0p, v1p, v2p}, *const vq[3] = {v0q, v1q, v2q};
  for (int k = 0; k < 3; k++) {
    const double yp = *vp[k], yq = *vq[k];
    *vp[k] = yp - s * (yq + h * yp);                               /* c v_kp - s v_kq */
    *vq[k] = yq + s * (yp - h * yq);                               /* s v_kp + c v_kq */
  }
}

/* One cyclic sweep, planes (0,1), (0,2), (1,2); identity: v = I on entry
 * (the first sweep). */
HYPER_INLINE void jacobi_sweep(double a[6], double v[9], int identity)
{
  jacobi_rotate(&a[0], &a[1], &a[3], &a[5], &a[4], &v[0], &v[1], &v[3], &v[4], &v[6], &v[7],
                identity);                                         /* (0,1), r = 2 */
  jacobi_rotate(&a[0], &a[2], &a[5], &a[3], &a[4], &v[0], &v[2], &v[3], &v[5], &v[6], &v[8],
                0);                                                /* (0,2), r = 1 */
  jacobi_rotate(&a[1], &a[2], &a[4], &a[3], &a[5], &v[1], &v[2], &v[4], &v[5], &v[7], &v[8],
                0);                                                /* (1,2), r = 0 */
}

/* Converged: every a_pq negligible. */
HYPER_INLINE int jacobi_converged(const double a[6])
{
  return jacobi_negligible(a[0], a[1], a[3]) && jacobi_negligible(a[0], a[2], a[5]) &&
         jacobi_negligible(a[1], a[2], a[4]);
}

#endif
