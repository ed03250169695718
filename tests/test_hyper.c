/* test_hyper.c: the hyperelastic NGF point update (MODEL.md section 7,
 * src/material/hyper.c) and the 3x3 algebra under it, tested from their
 * definitions: the general 3x3 helpers of tensor3.h; the Jacobi
 * eigen-decomposition; the polar decomposition (near the identity, for
 * random stretches and for rotations up to 180 degrees); the log/exp round
 * trip; the branch-free ln(1 + x) and exp(x) of the update against long
 * double; the Hencky stress of a uniaxial stretch against its closed form;
 * objectivity of the elastic and of the dense plastic update; the order of
 * the F update; rate and path independence of the elastic response; the
 * plastic return (tau, direction, the reused NGF root, the flow rule, det Fp,
 * the stored state giving back the returned stress); steady simple shear in
 * the local limit against mu(I); the state decisions; the batch update
 * against the point update, bit for bit.
 *
 * Tolerances are multiples of eps = DBL_EPSILON, each with its reason. The
 * recurring one: C = Fe^T Fe is formed in floating point, so whatever the
 * rotation its entries carry absolute errors of a few eps |Fe|^2; the Hencky
 * strain inherits them as an absolute error and the stress as that times the
 * moduli, so stresses are compared to 64 eps (3K + 2G) (|Fe| <= 1.5 here,
 * the observed errors are below 8 eps (3K + 2G)). */
#include <check.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/points.h"
#include "core/tensor3.h"
#include "material/hyper.h"
#include "material/material.h"

#define EPS DBL_EPSILON
#define PI 3.14159265358979323846

/* [DK15] Table 1 granular values with [DK-silo] A and t0, E = 1 MPa. */
static mpm_material_params params(int form)
{
  mpm_material_params par = {.E = 1e6, .nu = 0.3, .rho_s = 2450.0, .rho_c = 1500.0,
                             .mu_s = 0.3819, .mu_2 = 0.6435, .I0 = 0.279, .d = 0.005,
                             .A = 0.48, .t0 = 1e-3, .form = form};
  mpm_material_params_derive(&par);
  return par;
}

/* The stress tolerance of the banner: 64 eps (3K + 2G). */
static double stress_tol(const mpm_material_params *par)
{
  return 64.0 * EPS * (3.0 * par->K + 2.0 * par->G);
}

/* Deterministic pseudo-random numbers in [0, 1) (no global state). */
static double lcg(unsigned long *s)
{
  *s = *s * 6364136223846793005UL + 1442695040888963407UL;
  return (double)(*s >> 11) / 9007199254740992.0;
}

/* Uniform in [-1, 1). */
static double sym_rand(unsigned long *s)
{
  return 2.0 * lcg(s) - 1.0;
}

static mpm_mat3 rand_mat(unsigned long *s, double scale)
{
  mpm_mat3 a;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      a.m[i][j] = scale * sym_rand(s);
  return a;
}

static mpm_sym3 rand_sym(unsigned long *s, double scale)
{
  return (mpm_sym3){scale * sym_rand(s), scale * sym_rand(s), scale * sym_rand(s),
                    scale * sym_rand(s), scale * sym_rand(s), scale * sym_rand(s)};
}

/* Rotation by angle t about the axis (x, y, z) (normalised here), Rodrigues:
 * R = I + sin t K + (1 - cos t) K^2, K the cross-product matrix of the axis. */
static mpm_mat3 rotation(double x, double y, double z, double t)
{
  double n = sqrt(x * x + y * y + z * z);
  x /= n;
  y /= n;
  z /= n;
  mpm_mat3 K = {{{0.0, -z, y}, {z, 0.0, -x}, {-y, x, 0.0}}};
  mpm_mat3 K2 = mpm_mat3_mul(&K, &K), R = mpm_mat3_identity();
  double s = sin(t), c = 1.0 - cos(t);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      R.m[i][j] += s * K.m[i][j] + c * K2.m[i][j];
  return R;
}

/* A random rotation: random axis, angle in [0, pi]. */
static mpm_mat3 rand_rotation(unsigned long *s)
{
  double x = sym_rand(s), y = sym_rand(s), z = sym_rand(s);
  return rotation(x + 1e-3, y, z, PI * lcg(s));
}

static double mat3_maxabs(const mpm_mat3 *a)
{
  double m = 0.0;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      m = fabs(a->m[i][j]) > m ? fabs(a->m[i][j]) : m;
  return m;
}

static double mat3_maxdiff(const mpm_mat3 *a, const mpm_mat3 *b)
{
  double m = 0.0;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      m = fabs(a->m[i][j] - b->m[i][j]) > m ? fabs(a->m[i][j] - b->m[i][j]) : m;
  return m;
}

static double sym3_maxabs(mpm_sym3 s)
{
  double v[6] = {s.xx, s.yy, s.zz, s.xy, s.yz, s.zx}, m = 0.0;
  for (int i = 0; i < 6; i++)
    m = fabs(v[i]) > m ? fabs(v[i]) : m;
  return m;
}

static double sym3_maxdiff(mpm_sym3 a, mpm_sym3 b)
{
  return sym3_maxabs(mpm_sym3_axpy(a, -1.0, b));
}

/* |a^T a - I|_max: distance from orthogonality. */
static double orth_err(const mpm_mat3 *a)
{
  mpm_mat3 at = mpm_mat3_transpose(a), p = mpm_mat3_mul(&at, a), I = mpm_mat3_identity();
  return mat3_maxdiff(&p, &I);
}

/* q s q^T written out as a triple loop, independent of mpm_sym3_congruence. */
static mpm_sym3 rotate_ref(const mpm_mat3 *q, mpm_sym3 s)
{
  mpm_mat3 S = mpm_sym3_full(s);
  double c[3][3] = {{0.0}};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      for (int k = 0; k < 3; k++)
        for (int l = 0; l < 3; l++)
          c[i][j] += q->m[i][k] * S.m[k][l] * q->m[j][l];
  return (mpm_sym3){c[0][0], c[1][1], c[2][2], c[0][1], c[1][2], c[0][2]};
}

/* q a q^T for a general a (rotating a velocity gradient). */
static mpm_mat3 rotate_mat(const mpm_mat3 *q, const mpm_mat3 *a)
{
  mpm_mat3 qt = mpm_mat3_transpose(q), t = mpm_mat3_mul(q, a);
  return mpm_mat3_mul(&t, &qt);
}

/* A point with deformation (F, Fp), stress sigma and NGF inputs. */
static mpm_material_hyper_point hpoint(mpm_mat3 F, mpm_mat3 Fp, mpm_sym3 sigma, double rho,
                                       double g, double lap)
{
  return (mpm_material_hyper_point){.F = F, .Fp = Fp, .sigma = sigma, .rho = rho, .g = g,
                                    .lap = lap, .state = MPM_STATE_DENSE};
}

/* ------------------------------------------------------------------ */

/* tensor3.h: a a^-1 = I, det(a b) = det a det b, det a^T = det a, (a b)^T =
 * b^T a^T and the congruence a s a^T against the triple loop, for random
 * matrices with det a away from 0 (|det a| > 0.05, entries in [-1, 1], so
 * cond(a) < 1e3 and the inverse is good to 1e3 eps; products and
 * determinants of such entries are exact to a few eps of their size). */
START_TEST(t_mat3_helpers)
{
  unsigned long s = 11u;
  int n = 0;
  while (n < 2000) {
    mpm_mat3 a = rand_mat(&s, 1.0), b = rand_mat(&s, 1.0);
    double da = mpm_mat3_det(&a), db = mpm_mat3_det(&b);
    if (fabs(da) < 0.05)
      continue;
    n++;
    mpm_mat3 ai = mpm_mat3_inverse(&a), p = mpm_mat3_mul(&a, &ai), I = mpm_mat3_identity();
    ck_assert_msg(mat3_maxdiff(&p, &I) < 1e3 * EPS, "a a^-1 - I = %g", mat3_maxdiff(&p, &I));
    mpm_mat3 ab = mpm_mat3_mul(&a, &b);
    ck_assert(fabs(mpm_mat3_det(&ab) - da * db) < 32.0 * EPS);
    mpm_mat3 at = mpm_mat3_transpose(&a), bt = mpm_mat3_transpose(&b);
    ck_assert(fabs(mpm_mat3_det(&at) - da) < 16.0 * EPS);
    mpm_mat3 abt = mpm_mat3_transpose(&ab), btat = mpm_mat3_mul(&bt, &at);
    ck_assert(mat3_maxdiff(&abt, &btat) == 0.0);        /* the same sums, same order */
    mpm_sym3 sy = rand_sym(&s, 1.0);
    ck_assert(sym3_maxdiff(mpm_sym3_congruence(&a, sy), rotate_ref(&a, sy)) < 32.0 * EPS);
  }
  mpm_mat3 I = mpm_mat3_identity();
  ck_assert_double_eq(mpm_mat3_det(&I), 1.0);
}
END_TEST

/* Jacobi eigenpairs: a v = v diag(lam) and v^T v = I to 16 eps |a| and
 * 16 eps (each rotation is orthogonal to a few eps and a 3x3 needs about a
 * dozen), for random matrices, matrices with a double or triple eigenvalue,
 * graded ones, one whose rotation angle has theta = 5e159 (beyond the range
 * where theta^2 is finite) and the zero matrix. */
START_TEST(t_eigen)
{
  unsigned long s = 5u;
  for (int n = 0; n < 3000; n++) {
    mpm_sym3 a;
    int kind = n % 4;
    if (kind == 0)
      a = rand_sym(&s, 1.0);
    else {
      double d[3] = {sym_rand(&s), sym_rand(&s), sym_rand(&s)};
      if (kind == 1)
        d[1] = d[0];                                       /* double eigenvalue */
      else if (kind == 2)
        d[1] = d[2] = d[0];                                /* triple */
      else {
        d[1] *= 1e-8;                                      /* graded */
        d[2] *= 1e-16;
      }
      mpm_mat3 q = rand_rotation(&s);
      a = mpm_sym3_congruence(&q, (mpm_sym3){d[0], d[1], d[2], 0.0, 0.0, 0.0});
    }
    double lam[3];
    mpm_mat3 v;
    mpm_material_hyper_eigen(a, lam, &v);
    mpm_mat3 A = mpm_sym3_full(a), av = mpm_mat3_mul(&A, &v), vl = v;
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++)
        vl.m[i][j] *= lam[j];
    double na = sym3_maxabs(a);
    ck_assert_msg(mat3_maxdiff(&av, &vl) <= 16.0 * EPS * na, "case %d: residual %g of %g", n,
                  mat3_maxdiff(&av, &vl), na);
    ck_assert_msg(orth_err(&v) <= 16.0 * EPS, "case %d: v^T v - I = %g", n, orth_err(&v));
  }
  double lam[3];
  mpm_mat3 v, I = mpm_mat3_identity();
  const mpm_sym3 wide = {1.0, 1e-300, 0.5, 1e-160, 0.0, 0.0};    /* a_xy above the drop bar */
  mpm_material_hyper_eigen(wide, lam, &v);
  mpm_mat3 W = mpm_sym3_full(wide), wv = mpm_mat3_mul(&W, &v), wl = v;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      wl.m[i][j] *= lam[j];
  ck_assert_msg(mat3_maxdiff(&wv, &wl) <= 16.0 * EPS, "theta = 5e159: residual %g",
                mat3_maxdiff(&wv, &wl));
  ck_assert_msg(orth_err(&v) <= 16.0 * EPS, "theta = 5e159: v^T v - I = %g", orth_err(&v));
  mpm_material_hyper_eigen(mpm_sym3_zero(), lam, &v);
  ck_assert(lam[0] == 0.0 && lam[1] == 0.0 && lam[2] == 0.0 && mat3_maxdiff(&v, &I) == 0.0);
}
END_TEST

/* Jacobi on the kinds of matrix the update meets, 2000 of each: C - I of
 * F = R (I + e X) for e = 1e-2, 1e-6, 1e-12 (near-identity stretches turned
 * by random rotations R; entries of X in [-1, 1]); A = Q diag(d) Q^T with two
 * eigenvalues d, d (1 + delta) and with three within delta, delta = 1e-3,
 * 1e-8, 1e-14 and 0 (nearly degenerate); graded d = (1, 1e-8, 1e-16). The
 * residual a v - v diag(lam) and v^T v - I to 8 eps |a| and 8 eps (the
 * largest measured over 200,000 of each: 6 eps and 4 eps), and, for the
 * built A, the sorted eigenvalues against d to 20 eps max|d|: A itself is
 * Q diag(d) Q^T rounded, each entry off by up to 4 eps max|d| (three
 * products and two sums), which moves the spectrum by up to three times that
 * (the 2-norm of a 3x3 is below 3 times its largest entry), and Jacobi adds
 * its 6 eps. A plane-strain matrix (a_yz =
 * a_zx = 0) keeps its zeros exactly: lam_z = a_zz and v = diag(v2, 1), the
 * zero rotations in the planes (x, z), (y, z) changing nothing. */
static void sort3(double d[3])
{
  for (int i = 0; i < 2; i++)
    for (int j = 0; j < 2 - i; j++)
      if (d[j] > d[j + 1]) {
        const double t = d[j];
        d[j] = d[j + 1];
        d[j + 1] = t;
      }
}

static void check_eigen(mpm_sym3 a, const double *d, const char *kind, int n)
{
  double lam[3];
  mpm_mat3 v;
  mpm_material_hyper_eigen(a, lam, &v);
  mpm_mat3 A = mpm_sym3_full(a), av = mpm_mat3_mul(&A, &v), vl = v;
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      vl.m[i][j] *= lam[j];
  const double na = sym3_maxabs(a);
  ck_assert_msg(mat3_maxdiff(&av, &vl) <= 8.0 * EPS * na, "%s %d: residual %g of %g", kind, n,
                mat3_maxdiff(&av, &vl), na);
  ck_assert_msg(orth_err(&v) <= 8.0 * EPS, "%s %d: v^T v - I = %g", kind, n, orth_err(&v));
  if (d) {
    double l[3] = {lam[0], lam[1], lam[2]}, r[3] = {d[0], d[1], d[2]};
    sort3(l);
    sort3(r);
    const double nd = fmax(fabs(r[0]), fabs(r[2]));
    for (int i = 0; i < 3; i++)
      ck_assert_msg(fabs(l[i] - r[i]) <= 20.0 * EPS * nd, "%s %d: eigenvalue %.17g, built %.17g",
                    kind, n, l[i], r[i]);
  }
}

START_TEST(t_eigen_kinds)
{
  unsigned long s = 17u;
  const double es[] = {1e-2, 1e-6, 1e-12};
  for (size_t k = 0; k < sizeof es / sizeof es[0]; k++)
    for (int n = 0; n < 2000; n++) {
      mpm_mat3 R = rand_rotation(&s), X = rand_mat(&s, es[k]);
      for (int i = 0; i < 3; i++)
        X.m[i][i] += 1.0;
      const mpm_mat3 F = mpm_mat3_mul(&R, &X), Ft = mpm_mat3_transpose(&F);
      mpm_mat3 C = mpm_mat3_mul(&Ft, &F);
      const mpm_sym3 cmi = {C.m[0][0] - 1.0, C.m[1][1] - 1.0, C.m[2][2] - 1.0, C.m[0][1],
                            C.m[1][2], C.m[0][2]};
      check_eigen(cmi, NULL, "C - I", n);
    }
  const double deltas[] = {1e-3, 1e-8, 1e-14, 0.0};
  for (size_t k = 0; k < sizeof deltas / sizeof deltas[0]; k++)
    for (int three = 0; three < 2; three++)
      for (int n = 0; n < 2000; n++) {
        const double d0 = sym_rand(&s), dl = deltas[k];
        double d[3] = {d0, d0 * (1.0 + dl * sym_rand(&s)),
                       three ? d0 * (1.0 + dl * sym_rand(&s)) : sym_rand(&s)};
        const mpm_mat3 q = rand_rotation(&s);
        check_eigen(mpm_sym3_congruence(&q, (mpm_sym3){d[0], d[1], d[2], 0.0, 0.0, 0.0}), d,
                    three ? "three close" : "two close", n);
      }
  for (int n = 0; n < 2000; n++) {
    double d[3] = {sym_rand(&s), 1e-8 * sym_rand(&s), 1e-16 * sym_rand(&s)};
    const mpm_mat3 q = rand_rotation(&s);
    const mpm_sym3 a = mpm_sym3_congruence(&q, (mpm_sym3){d[0], d[1], d[2], 0.0, 0.0, 0.0});
    check_eigen(a, NULL, "graded", n);
  }
  for (int n = 0; n < 200; n++) {
    const mpm_sym3 a = {sym_rand(&s), sym_rand(&s), sym_rand(&s), sym_rand(&s), 0.0, 0.0};
    double lam[3];
    mpm_mat3 v;
    mpm_material_hyper_eigen(a, lam, &v);
    ck_assert(lam[2] == a.zz && v.m[2][2] == 1.0);
    ck_assert(v.m[0][2] == 0.0 && v.m[1][2] == 0.0 && v.m[2][0] == 0.0 && v.m[2][1] == 0.0);
    check_eigen(a, NULL, "plane", n);
  }
}
END_TEST

/* Polar decomposition F = R U: R orthogonal and det R = 1, U symmetric
 * (by its type) positive definite, R U = F, for (a) random stretches
 * F = Q1 diag(s) Q2, s in [0.5, 2], (b) near-identity F = I + 1e-8 X,
 * (c) rotations of 179 and 180 degrees times a near-identity stretch,
 * (d) general random F with det F > 0.1.
 * Tolerances: R U = F to 1e-13 relative and R^T R = I to 1e-13: the error is
 * about eps cond(F)^2 (C squares the condition number; hyper.c), and
 * cond(F) <= 4 in (a)-(c); (d) has cond up to a few hundred, hence its own
 * looser bound of 1e3 eps cond(F)^2 for orthogonality. */
START_TEST(t_polar)
{
  unsigned long s = 99u;
  for (int n = 0; n < 4000; n++) {
    int kind = n % 4;
    mpm_mat3 F;
    double cond2 = 16.0;                                   /* cond(F)^2 bound */
    if (kind == 0) {
      mpm_mat3 q1 = rand_rotation(&s), q2 = rand_rotation(&s);
      mpm_mat3 d = {{{0.5 + 1.5 * lcg(&s), 0, 0}, {0, 0.5 + 1.5 * lcg(&s), 0},
                     {0, 0, 0.5 + 1.5 * lcg(&s)}}};
      mpm_mat3 t = mpm_mat3_mul(&q1, &d);
      F = mpm_mat3_mul(&t, &q2);
    } else if (kind == 1) {
      F = rand_mat(&s, 1e-8);
      for (int i = 0; i < 3; i++)
        F.m[i][i] += 1.0;
    } else if (kind == 2) {
      double ang = (n % 8 == 2 ? 179.0 : 180.0) * PI / 180.0;
      mpm_mat3 q = rotation(sym_rand(&s), sym_rand(&s), sym_rand(&s) + 1e-3, ang);
      mpm_mat3 u = rand_mat(&s, 1e-3);
      for (int i = 0; i < 3; i++)
        u.m[i][i] += 1.0;
      F = mpm_mat3_mul(&q, &u);
    } else {
      F = rand_mat(&s, 1.0);
      if (mpm_mat3_det(&F) < 0.1) {
        n--;
        continue;
      }
      mpm_mat3 Fi = mpm_mat3_inverse(&F);
      double c = 3.0 * mat3_maxabs(&F) * 3.0 * mat3_maxabs(&Fi);   /* >= cond_2(F) */
      cond2 = c * c;
    }
    mpm_mat3 R;
    mpm_sym3 U;
    mpm_material_hyper_polar(&F, &R, &U);
    mpm_mat3 Uf = mpm_sym3_full(U), RU = mpm_mat3_mul(&R, &Uf);
    double rel = mat3_maxdiff(&RU, &F) / mat3_maxabs(&F);
    double orth_tol = kind == 3 ? 1e3 * EPS * cond2 : 1e-13;
    ck_assert_msg(rel <= 1e-13, "case %d: |RU - F|/|F| = %g", n, rel);
    ck_assert_msg(orth_err(&R) <= orth_tol, "case %d: R^T R - I = %g", n, orth_err(&R));
    ck_assert_msg(fabs(mpm_mat3_det(&R) - 1.0) <= orth_tol, "case %d: det R = %.17g", n,
                  mpm_mat3_det(&R));
    double lam[3];
    mpm_mat3 v;
    mpm_material_hyper_eigen(U, lam, &v);
    ck_assert(lam[0] > 0.0 && lam[1] > 0.0 && lam[2] > 0.0);
  }
  /* A pure rotation of 180 degrees: U = I and R = F to a few eps. */
  mpm_mat3 Q = rotation(1.0, 2.0, 3.0, PI), R;
  mpm_sym3 U;
  mpm_material_hyper_polar(&Q, &R, &U);
  ck_assert(sym3_maxdiff(U, (mpm_sym3){1, 1, 1, 0, 0, 0}) <= 8.0 * EPS);
  ck_assert(mat3_maxdiff(&R, &Q) <= 8.0 * EPS);
}
END_TEST

/* ln and exp: exp(ln A) = A for SPD A = Q diag(l) Q^T, l in [0.1, 10], to
 * 64 eps |A| (ln A has entries up to ln 10 = 2.3; exp scales their absolute
 * error by up to 10); ln(exp S) = S for symmetric S with entries in [-1, 1]
 * to 64 eps e^(3|S|max) (|S|max bounds the eigenvalues by 3 |S|max; exp
 * and ln scale the absolute errors by up to that); diagonal values against
 * log/exp; near the identity, A = I + h with |h| ~ 1e-12,
 * ln A = h - h^2/2 + O(h^3) to 16 eps |h|: the logarithm keeps the relative
 * accuracy of the small strain h (log1p of A - I, which is exact), where ln
 * of the eigenvalues of A itself would lose it to eps/|h|. */
START_TEST(t_log_exp)
{
  unsigned long s = 3u;
  for (int n = 0; n < 2000; n++) {
    mpm_mat3 q = rand_rotation(&s);
    double l[3] = {0.1 * pow(100.0, lcg(&s)), 0.1 * pow(100.0, lcg(&s)),
                   0.1 * pow(100.0, lcg(&s))};
    mpm_sym3 A = mpm_sym3_congruence(&q, (mpm_sym3){l[0], l[1], l[2], 0, 0, 0});
    mpm_sym3 back = mpm_material_hyper_exp(mpm_material_hyper_log(A));
    ck_assert_msg(sym3_maxdiff(back, A) <= 64.0 * EPS * sym3_maxabs(A), "case %d: %g", n,
                  sym3_maxdiff(back, A) / sym3_maxabs(A));
    mpm_sym3 S = rand_sym(&s, 1.0);
    mpm_sym3 S2 = mpm_material_hyper_log(mpm_material_hyper_exp(S));
    ck_assert_msg(sym3_maxdiff(S2, S) <= 64.0 * EPS * exp(3.0 * sym3_maxabs(S)), "case %d: %g",
                  n, sym3_maxdiff(S2, S));
  }
  mpm_sym3 d = mpm_material_hyper_log((mpm_sym3){0.5, 2.0, 7.0, 0, 0, 0});
  ck_assert(fabs(d.xx - log(0.5)) <= 2.0 * EPS && fabs(d.yy - log(2.0)) <= 2.0 * EPS
            && fabs(d.zz - log(7.0)) <= 4.0 * EPS && d.xy == 0.0 && d.yz == 0.0 && d.zx == 0.0);
  mpm_sym3 e = mpm_material_hyper_exp((mpm_sym3){-1.0, 0.0, 2.0, 0, 0, 0});
  ck_assert(fabs(e.xx - exp(-1.0)) <= 2.0 * EPS && e.yy == 1.0
            && fabs(e.zz - exp(2.0)) <= 8.0 * EPS);
  for (int n = 0; n < 200; n++) {
    mpm_sym3 A = mpm_sym3_add_iso(rand_sym(&s, 1e-12), 1.0);
    mpm_sym3 h = mpm_sym3_add_iso(A, -1.0);              /* exact: entries near 1 */
    mpm_mat3 hf = mpm_sym3_full(h), h2 = mpm_mat3_mul(&hf, &hf);
    mpm_sym3 ref = mpm_sym3_axpy(h, -0.5, mpm_mat3_sym(&h2));   /* h - h^2/2, to 1e-24 |h| */
    mpm_sym3 ln = mpm_material_hyper_log(A);
    ck_assert_msg(sym3_maxdiff(ln, ref) <= 16.0 * EPS * sym3_maxabs(h), "case %d: %g of %g", n,
                  sym3_maxdiff(ln, ref), sym3_maxabs(h));
  }
  /* Not positive definite: NaN, never a number. */
  mpm_sym3 bad = mpm_material_hyper_log((mpm_sym3){1.0, -1.0, 1.0, 0, 0, 0});
  ck_assert(isnan(bad.yy));
}
END_TEST

/* Error of got in units in the last place of the double nearest the
 * reference ref: |got - ref| / ulp (subnormal spacing below DBL_MIN);
 * 0 when both are the same infinity or NaN, inf when only one is. */
static double ulp_error(double got, long double ref)
{
  if (isnan(ref) || isinf(ref))
    return (isnan(ref) && isnan(got)) || got == ref ? 0.0 : INFINITY;
  const double r = fabs((double)ref);
  const double ulp = r >= DBL_MIN ? ldexp(1.0, ilogb(r) - (DBL_MANT_DIG - 1))
                                  : ldexp(1.0, DBL_MIN_EXP - DBL_MANT_DIG);
  return (double)(fabsl((long double)got - ref) / ulp);
}

/* The error of ln(1 + x) (of exp(x)) at x in ulp against the reference
 * (long double when ext), kept in *worst with its x in *at when larger. */
static void note_worst(double e, double x, double *worst, double *at)
{
  if (e > *worst) {
    *worst = e;
    *at = x;
  }
}

static void note_log1p(double x, int ext, double *worst, double *at)
{
  const long double ref = ext ? log1pl((long double)x) : (long double)log1p(x);
  note_worst(ulp_error(mpm_material_hyper_log1p(x), ref), x, worst, at);
}

static void note_exp(double x, int ext, double *worst, double *at)
{
  const long double ref = ext ? expl((long double)x) : (long double)exp(x);
  note_worst(ulp_error(mpm_material_hyper_exp_scalar(x), ref), x, worst, at);
}

/* The ln(1 + x) and exp(x) of the update (mpm_material_hyper_log1p,
 * _exp_scalar; branch-free, see hyper.c) against long double over dense
 * sweeps: ln(1 + x) for x = +-10^k, k from -320 to 300 in steps of 1e-3, for
 * x = -1 + 10^-k (k to 16.5) and for x from -0.5 to 3 in steps of 2^-17;
 * exp(x) for x from -746 to 710 in steps of 1e-3 (subnormal results
 * included, in units of their spacing) and x = +-10^k, k from -320 to 2.8.
 * Both errors stay below 1 ulp (measured here: 0.815 and 0.874), the
 * reference (64-bit significand) adds 2^-11 ulp at most. Then the special
 * values: -1, below -1, +-inf, NaN, zeros, the overflow and underflow
 * thresholds; a tiny x is its own ln(1 + x). Without an extended long
 * double the reference is the C library's, to 2 ulp. */
START_TEST(t_log1p_exp)
{
  const int ext = LDBL_MANT_DIG >= 64;
  const double tol = ext ? 1.0 : 2.0;
  double worst = 0.0, at = 0.0;
  for (int sg = -1; sg <= 1; sg += 2)
    for (int k = -320000; k <= 300000; k++) {
      const double x = sg * pow(10.0, k * 1e-3);
      if (x > -1.0)
        note_log1p(x, ext, &worst, &at);
    }
  for (double k = 0.0; k <= 16.5; k += 1e-5)
    note_log1p(-1.0 + pow(10.0, -k), ext, &worst, &at);
  for (double x = -0.5; x <= 3.0; x += 0x1p-17)
    note_log1p(x, ext, &worst, &at);
  ck_assert_msg(worst < tol, "ln(1 + x): %.3f ulp at x = %.17g", worst, at);
  worst = 0.0;
  for (int k = -746000; k <= 710000; k++)
    note_exp(k * 1e-3, ext, &worst, &at);
  for (int sg = -1; sg <= 1; sg += 2)
    for (int k = -320000; k <= 2800; k++)
      note_exp(sg * pow(10.0, k * 1e-3), ext, &worst, &at);
  ck_assert_msg(worst < tol, "exp(x): %.3f ulp at x = %.17g", worst, at);
  ck_assert(mpm_material_hyper_log1p(-1.0) == -INFINITY);
  ck_assert(isnan(mpm_material_hyper_log1p(-1.5)) && isnan(mpm_material_hyper_log1p(-INFINITY)));
  ck_assert(mpm_material_hyper_log1p(INFINITY) == INFINITY);
  ck_assert(isnan(mpm_material_hyper_log1p(NAN)));
  ck_assert(mpm_material_hyper_log1p(0.0) == 0.0 && mpm_material_hyper_log1p(-0.0) == 0.0);
  ck_assert(mpm_material_hyper_log1p(1e-300) == 1e-300);
  ck_assert(mpm_material_hyper_log1p(-0x1p-60) == -0x1p-60);
  ck_assert(mpm_material_hyper_exp_scalar(0.0) == 1.0);
  ck_assert(mpm_material_hyper_exp_scalar(-INFINITY) == 0.0);
  ck_assert(mpm_material_hyper_exp_scalar(INFINITY) == INFINITY);
  ck_assert(isnan(mpm_material_hyper_exp_scalar(NAN)));
  ck_assert(isfinite(mpm_material_hyper_exp_scalar(709.78)));
  ck_assert(mpm_material_hyper_exp_scalar(709.79) == INFINITY);
  ck_assert(mpm_material_hyper_exp_scalar(-745.2) == 0.0);
  ck_assert(mpm_material_hyper_exp_scalar(-745.0) > 0.0);   /* the smallest subnormal */
}
END_TEST

/* Uniaxial stretch F = diag(lambda, 1, 1), Fp = I: Ee = diag(ln lambda, 0, 0),
 * Me = 2G dev(Ee) + K tr(Ee) I, sigma = Me / lambda (J = lambda, R = I), for
 * lambda from 0.5 to 2 and 1 + 1e-9 (where the strain keeps its relative
 * accuracy: log1p of lambda - 1, an exact difference). Tolerance 16 eps of
 * the stress: C - I = diag(2h + h^2) with h = lambda - 1 exact, and the rest
 * is a handful of roundings. The same stretch turned by Q gives Q sigma Q^T
 * (stress tolerance of the banner). */
START_TEST(t_uniaxial_hencky)
{
  const mpm_material_params par = params(MPM_NGF_DK);
  const double lams[] = {0.5, 0.8, 0.99, 1.0 + 1e-9, 1.0, 1.01, 1.25, 1.5, 2.0};
  mpm_mat3 I = mpm_mat3_identity();
  for (size_t k = 0; k < sizeof lams / sizeof lams[0]; k++) {
    double lam = lams[k], e = log1p(lam - 1.0);
    mpm_sym3 Ee = {e, 0, 0, 0, 0, 0};
    mpm_sym3 Me = mpm_sym3_add_iso(mpm_sym3_scale(mpm_sym3_dev(Ee), 2.0 * par.G), par.K * e);
    mpm_sym3 ref = mpm_sym3_scale(Me, 1.0 / lam);
    mpm_mat3 F = {{{lam, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    mpm_sym3 sig = mpm_material_hyper_stress(&par, &F, &I);
    double scale = sym3_maxabs(ref);
    ck_assert_msg(sym3_maxdiff(sig, ref) <= 16.0 * EPS * scale, "lambda %g: %g of %g", lam,
                  sym3_maxdiff(sig, ref), scale);
    if (lam == 1.0)
      ck_assert(sym3_maxabs(sig) == 0.0);
    /* the elastic step from the reference state with dt L = F - I */
    mpm_mat3 L = {{{lam - 1.0, 0, 0}, {0, 0, 0}, {0, 0, 0}}};
    mpm_material_hyper_point pt = hpoint(I, I, mpm_sym3_zero(), 2000.0, 0.0, 0.0);
    pt = mpm_material_hyper_elastic_step(&par, &L, 1.0, pt);
    ck_assert(sym3_maxdiff(pt.sigma, ref) <= 16.0 * EPS * scale);
    mpm_mat3 Q = rotation(1.0, -2.0, 0.5, 2.0);
    mpm_mat3 QF = mpm_mat3_mul(&Q, &F);
    ck_assert(sym3_maxdiff(mpm_material_hyper_stress(&par, &QF, &I), rotate_ref(&Q, ref))
              <= stress_tol(&par));
  }
}
END_TEST

/* The elastic state of an initial stress (mpm_material_hyper_F_of_stress):
 * for random compressive stresses, turned by random rotations, up to 10 %
 * of K in pressure and deviator, F is symmetric and gives the stress back
 * (to the banner's tolerance); the lithostatic state of a fill (sigma_yy =
 * -1e4 Pa, sigma_xx = sigma_zz = K0 sigma_yy) a diagonal stretch along y
 * alone to first order (uniaxial strain), and a zero stress the identity. */
START_TEST(t_F_of_stress)
{
  const mpm_material_params par = params(MPM_NGF_DK);
  const mpm_mat3 I = mpm_mat3_identity();
  unsigned long s = 77;
  for (int k = 0; k < 200; k++) {
    const double p = 0.1 * par.K * lcg(&s);
    mpm_sym3 d = mpm_sym3_dev(rand_sym(&s, 0.1 * par.K));
    mpm_mat3 q = rand_rotation(&s);
    const mpm_sym3 sig = mpm_sym3_add_iso(mpm_sym3_congruence(&q, d), -p);
    const mpm_mat3 F = mpm_material_hyper_F_of_stress(&par, sig);
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++)
        ck_assert(fabs(F.m[i][j] - F.m[j][i]) <= 16.0 * EPS);
    const mpm_sym3 back = mpm_material_hyper_stress(&par, &F, &I);
    ck_assert_msg(sym3_maxdiff(back, sig) <= stress_tol(&par), "%d: %g", k,
                  sym3_maxdiff(back, sig));
  }
  const double k0 = par.nu / (1.0 - par.nu);
  const mpm_sym3 lith = {k0 * -1e4, -1e4, k0 * -1e4, 0, 0, 0};
  const mpm_mat3 F = mpm_material_hyper_F_of_stress(&par, lith);
  ck_assert(F.m[0][1] == 0.0 && F.m[1][2] == 0.0 && F.m[0][2] == 0.0);
  /* K0 is the uniaxial strain state: to first order only y shortens, by
   * sigma_yy / (K + 4G/3) = -7.4e-3; the rest is second order in p / K */
  ck_assert_double_eq_tol(F.m[1][1] - 1.0, -1e4 / (par.K + 4.0 * par.G / 3.0), 1e-4);
  ck_assert_double_eq_tol(F.m[0][0], 1.0, 1e-4);
  ck_assert_double_eq_tol(F.m[0][0], F.m[2][2], 1e-15);
  ck_assert(sym3_maxdiff(mpm_material_hyper_stress(&par, &F, &I), lith) <= stress_tol(&par));
  const mpm_mat3 F0 = mpm_material_hyper_F_of_stress(&par, mpm_sym3_zero());
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      ck_assert(F0.m[i][j] == (i == j ? 1.0 : 0.0));
}
END_TEST

/* A dense state: F_n = R0 (0.99 I + 0.003 X) (compressed, sheared, turned),
 * Fp_n = exp of a small deviator (isochoric), sigma_n its stress (p_n > 0). */
static mpm_material_hyper_point dense_state(const mpm_material_params *par, unsigned long *s,
                                            double g, double lap)
{
  mpm_mat3 R0 = rand_rotation(s), B = rand_mat(s, 0.003);
  for (int i = 0; i < 3; i++)
    B.m[i][i] += 0.99;
  mpm_mat3 F = mpm_mat3_mul(&R0, &B);
  mpm_sym3 a = mpm_sym3_dev(rand_sym(s, 0.05));
  mpm_mat3 Fp = mpm_sym3_full(mpm_material_hyper_exp(a));
  F = mpm_mat3_mul(&F, &Fp);                       /* Fe = F Fp^-1 = R0 B: compressed */
  mpm_sym3 sig = mpm_material_hyper_stress(par, &F, &Fp);
  return hpoint(F, Fp, sig, 2000.0, g, lap);
}

/* Objectivity: with F_n' = Q F_n, sigma_n' = Q sigma_n Q^T and L' = Q L Q^T
 * (a superposed rotation), the update gives F_{n+1}' = Q F_{n+1},
 * sigma' = Q sigma Q^T, Fp' = Fp and the same p, tau, g, gdot_p and state,
 * for rotations about several axes of up to 180 degrees, in the elastic
 * variant, the dense plastic update, the reconnecting step and the
 * disconnected one. Stresses to the banner's tolerance; g and gdot_p to
 * 1e-10 relative (the root is a smooth function of p and tau_tr, whose
 * absolute errors of 64 eps (3K + 2G) are 1e-12 of p ~ 1e4 Pa here, times a
 * conditioning below 100); F and Fp to 64 eps (a few products of entries of
 * size <= 1.5). A rigid rotation of any size of the stress-free state
 * leaves it stress-free. */
START_TEST(t_objectivity)
{
  const mpm_material_params par = params(MPM_NGF_DK);
  const double tol = stress_tol(&par);
  const double ang[] = {1e-6, 0.3, PI / 2, 2.5, 179.0 * PI / 180.0, PI};
  const double axes[][3] = {{0, 0, 1}, {1, 0, 0}, {1, 1, 1}, {-0.3, 2.0, 0.7}};
  unsigned long s = 2024u;
  const double dt = 1e-4;
  for (int kase = 0; kase < 4; kase++) {
    for (size_t ia = 0; ia < sizeof ang / sizeof ang[0]; ia++)
      for (size_t ix = 0; ix < sizeof axes / sizeof axes[0]; ix++) {
        mpm_material_hyper_point pt = dense_state(&par, &s, 20.0, 1e3);
        mpm_mat3 L = rand_mat(&s, 5.0);
        if (kase == 2) {                                   /* reconnecting */
          pt.sigma = mpm_sym3_zero();
          pt.g = 0.0;
        } else if (kase == 3) {                            /* disconnecting: tension */
          for (int i = 0; i < 3; i++)
            L.m[i][i] += 200.0;
        }
        mpm_mat3 Q = rotation(axes[ix][0], axes[ix][1], axes[ix][2], ang[ia]);
        mpm_material_hyper_point qt = pt;
        qt.F = mpm_mat3_mul(&Q, &pt.F);
        qt.sigma = rotate_ref(&Q, pt.sigma);
        mpm_mat3 QL = rotate_mat(&Q, &L);
        mpm_material_hyper_point a, b;
        if (kase == 0) {
          a = mpm_material_hyper_elastic_step(&par, &L, dt, pt);
          b = mpm_material_hyper_elastic_step(&par, &QL, dt, qt);
        } else {
          a = mpm_material_hyper_step(&par, &L, dt, pt);
          b = mpm_material_hyper_step(&par, &QL, dt, qt);
        }
        ck_assert_int_eq(a.state, b.state);
        ck_assert_int_eq(a.state, kase == 3 ? MPM_STATE_DISCONNECTED : MPM_STATE_DENSE);
        double ds = sym3_maxdiff(b.sigma, rotate_ref(&Q, a.sigma));
        ck_assert_msg(ds <= tol, "case %d angle %g axis %zu: |sigma' - Q sigma Q^T| = %g",
                      kase, ang[ia], ix, ds);
        ck_assert(fabs(mpm_sym3_pressure(b.sigma) - mpm_sym3_pressure(a.sigma)) <= tol);
        ck_assert(fabs(mpm_sym3_tau(b.sigma) - mpm_sym3_tau(a.sigma)) <= tol);
        ck_assert_msg(fabs(b.g - a.g) <= 1e-10 * a.g, "case %d: g %.17g vs %.17g", kase, a.g,
                      b.g);
        ck_assert(fabs(b.gdp - a.gdp) <= 1e-10 * a.gdp);
        mpm_mat3 QF = mpm_mat3_mul(&Q, &a.F);
        ck_assert(mat3_maxdiff(&b.F, &QF) <= 64.0 * EPS);
        if (kase == 3) {
          ck_assert(sym3_maxabs(a.sigma) == 0.0 && sym3_maxabs(b.sigma) == 0.0);
          ck_assert(mat3_maxdiff(&b.Fp, &QF) <= 64.0 * EPS);   /* Fp = F: Q F */
        } else
          ck_assert(mat3_maxdiff(&b.Fp, &a.Fp) <= 64.0 * EPS);
        if (kase == 1)
          ck_assert(a.g > 0.0 && mpm_sym3_pressure(a.sigma) > 0.0);
      }
  }
  /* Rigid rotations of the stress-free state. */
  mpm_mat3 I = mpm_mat3_identity();
  for (size_t ia = 0; ia < sizeof ang / sizeof ang[0]; ia++)
    for (size_t ix = 0; ix < sizeof axes / sizeof axes[0]; ix++) {
      mpm_mat3 Q = rotation(axes[ix][0], axes[ix][1], axes[ix][2], ang[ia]);
      ck_assert(sym3_maxabs(mpm_material_hyper_stress(&par, &Q, &I)) <= tol);
      mpm_material_hyper_point pt = hpoint(Q, I, mpm_sym3_zero(), 2000.0, 0.0, 0.0);
      mpm_mat3 L0 = {{{0.0}}};
      mpm_material_hyper_point a = mpm_material_hyper_step(&par, &L0, dt, pt);
      ck_assert(sym3_maxabs(a.sigma) <= tol);
      /* and from a prestrained state, Q on top rotates only */
      mpm_material_hyper_point d = dense_state(&par, &s, 0.0, 0.0);
      mpm_mat3 QF = mpm_mat3_mul(&Q, &d.F);
      ck_assert(sym3_maxdiff(mpm_material_hyper_stress(&par, &QF, &d.Fp),
                             rotate_ref(&Q, d.sigma)) <= tol);
    }
}
END_TEST

/* The F update is dF/dt = L F with L_ij = d v_i / d x_j: a body turned by 90
 * degrees about z and then stretched along the spatial x axis by
 * dt L = diag(0.2, 0, 0) has its tensile stress along spatial x (the uniaxial
 * closed form, R = I in the left stretch), not along its material X axis
 * (which now points along y). Tolerance as in t_uniaxial_hencky. */
START_TEST(t_F_update_order)
{
  const mpm_material_params par = params(MPM_NGF_DK);
  mpm_mat3 I = mpm_mat3_identity(), Q = rotation(0.0, 0.0, 1.0, PI / 2);
  mpm_material_hyper_point pt = hpoint(Q, I, mpm_sym3_zero(), 2000.0, 0.0, 0.0);
  mpm_mat3 L = {{{0.2, 0, 0}, {0, 0, 0}, {0, 0, 0}}};
  pt = mpm_material_hyper_elastic_step(&par, &L, 1.0, pt);
  double lam = 1.2, e = log(lam);
  mpm_sym3 Ee = {e, 0, 0, 0, 0, 0};
  mpm_sym3 ref = mpm_sym3_scale(
      mpm_sym3_add_iso(mpm_sym3_scale(mpm_sym3_dev(Ee), 2.0 * par.G), par.K * e), 1.0 / lam);
  ck_assert_msg(sym3_maxdiff(pt.sigma, ref) <= stress_tol(&par), "%g %g %g", pt.sigma.xx,
                pt.sigma.yy, ref.xx);
  ck_assert(pt.sigma.xx > pt.sigma.yy);
}
END_TEST

/* F(t) on two paths to the same end F(1) = Rz(1.2) (I + H):
 * path 0: Rz(1.2 t) (I + t H); path 1: I + 2t H for t < 1/2, then
 * Rz(1.2 (2t - 1)) (I + H). Each step takes dt L = (F_target - F_n) F_n^-1,
 * so F_n follows the path with an error of a few eps that does not accumulate
 * (each step aims at the exact target). */
static mpm_mat3 path_F(int path, const mpm_mat3 *H, double t)
{
  double a = path == 0 ? t : t < 0.5 ? 2.0 * t : 1.0;
  double th = path == 0 ? 1.2 * t : t < 0.5 ? 0.0 : 1.2 * (2.0 * t - 1.0);
  mpm_mat3 B = mpm_mat3_identity(), Rz = rotation(0.0, 0.0, 1.0, th);
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      B.m[i][j] += a * H->m[i][j];
  return mpm_mat3_mul(&Rz, &B);
}

/* Rate and path independence of the elastic response: the hyperelastic
 * stress depends on F alone, so the end stress of 1, 10 and 1000 steps along
 * either path agrees to the banner's stress tolerance (the end F agrees to a
 * few eps; nothing is integrated), where a hypoelastic (rate) update differs
 * by O(dt). */
START_TEST(t_rate_independence)
{
  const mpm_material_params par = params(MPM_NGF_DK);
  mpm_mat3 I = mpm_mat3_identity();
  mpm_mat3 H = {{{-0.05, 0.08, 0.01}, {0.02, 0.03, -0.04}, {0.0, 0.06, -0.02}}};
  const int steps[] = {1, 10, 1000};
  mpm_mat3 Fend = path_F(0, &H, 1.0);
  mpm_sym3 ref = mpm_material_hyper_stress(&par, &Fend, &I);
  ck_assert(sym3_maxabs(ref) > 1e4);
  for (int path = 0; path < 2; path++)
    for (size_t k = 0; k < sizeof steps / sizeof steps[0]; k++) {
      int n = steps[k];
      double dt = 1.0 / n;
      mpm_material_hyper_point pt = hpoint(I, I, mpm_sym3_zero(), 2000.0, 0.0, 0.0);
      for (int i = 0; i < n; i++) {
        mpm_mat3 Ft = path_F(path, &H, (double)(i + 1) / n), Fi = mpm_mat3_inverse(&pt.F);
        mpm_mat3 dF = Ft;
        for (int a = 0; a < 3; a++)
          for (int b = 0; b < 3; b++)
            dF.m[a][b] = (Ft.m[a][b] - pt.F.m[a][b]) / dt;
        mpm_mat3 L = mpm_mat3_mul(&dF, &Fi);               /* L = dF/dt F^-1 */
        pt = mpm_material_hyper_elastic_step(&par, &L, dt, pt);
      }
      ck_assert_msg(mat3_maxdiff(&pt.F, &Fend) <= 64.0 * EPS, "path %d, %d steps: F off by %g",
                    path, n, mat3_maxdiff(&pt.F, &Fend));
      ck_assert_msg(sym3_maxdiff(pt.sigma, ref) <= stress_tol(&par),
                    "path %d, %d steps: sigma off by %g", path, n,
                    sym3_maxdiff(pt.sigma, ref));
    }
}
END_TEST

/* The plastic return of a dense point under simple shear (L = gdot e_x e_y):
 * against the elastic trial of the same step (the elastic variant),
 *   p unchanged, tau = tau_tr p / (p + G dt g) (Mandel p = J p_cauchy,
 *   tau likewise: the ratio is that of the Cauchy invariants),
 *   dev sigma / tau = dev sigma_tr / tau_tr (the direction is kept),
 *   g = the root of the 2D local solve (mpm_material_ngf_fluidity with g*
 *   from mpm_material_ngf_gstar) at this p, tau_tr,
 *   gdot_p = g tau / p = (tau_tr - tau) / (G dt),
 *   det Fp = 1 to 1e-12, and the stored state (F, Fp) gives back the returned
 *   stress (mpm_material_hyper_stress) to the banner's tolerance;
 * then 2000 steps of shear: det Fp stays 1 to 1e-12 (each step multiplies it
 * by exp(tr dt Lp) = exp(O(eps)), a random walk of 2000 eps-steps), the
 * stored state keeps giving back the stress, the returns keep their form.
 * Ratios to 1e-12 relative: tau and tau_tr are each ~1e-13 relative here
 * (the banner's absolute error over tau ~ 1e3 Pa). */
START_TEST(t_plastic_return)
{
  for (int form = 0; form < 2; form++) {
    const mpm_material_params par = params(form);
    const double tol = stress_tol(&par), dt = 1e-4;
    mpm_mat3 I = mpm_mat3_identity();
    mpm_mat3 F0 = {{{0.995, 0, 0}, {0, 0.995, 0}, {0, 0, 0.995}}};
    mpm_material_hyper_point pt = hpoint(F0, I, mpm_material_hyper_stress(&par, &F0, &I),
                                         2000.0, 50.0, -2e3);
    pt.isp = 0.0;
    mpm_mat3 L = {{{0, 10.0, 0}, {0, 0, 0}, {0, 0, 0}}};
    int plastic = 0;
    for (int n = 0; n < 2000; n++) {
      mpm_material_hyper_point tr = mpm_material_hyper_elastic_step(&par, &L, dt, pt);
      mpm_material_hyper_point nx = mpm_material_hyper_step(&par, &L, dt, pt);
      ck_assert_int_eq(nx.state, MPM_STATE_DENSE);
      ck_assert(mat3_maxdiff(&nx.F, &tr.F) == 0.0);
      double J = mpm_mat3_det(&nx.F);
      double p = J * mpm_sym3_pressure(tr.sigma), tau_tr = J * mpm_sym3_tau(tr.sigma);
      double tau = J * mpm_sym3_tau(nx.sigma);
      ck_assert(fabs(J * mpm_sym3_pressure(nx.sigma) - p) <= J * tol);
      double p_n = mpm_sym3_pressure(pt.sigma);
      double mug_n = pt.g * mpm_sym3_tau(pt.sigma) / p_n;
      double gs = mpm_material_ngf_gstar(&par, dt, pt.g, pt.lap);
      double g = mpm_material_ngf_fluidity(&par, dt, p, tau_tr, gs, mug_n, 0.0);
      ck_assert_msg(fabs(nx.g - g) <= 1e-10 * g, "step %d: g %.17g, the 2D root %.17g", n,
                    nx.g, g);
      double ret = tau_tr * p / (p + par.G * dt * nx.g);
      ck_assert_msg(fabs(tau - ret) <= 1e-12 * tau, "step %d: tau %.17g, return %.17g", n,
                    tau, ret);
      mpm_sym3 dir = mpm_sym3_scale(mpm_sym3_dev(nx.sigma), 1.0 / mpm_sym3_tau(nx.sigma));
      mpm_sym3 dir_tr = mpm_sym3_scale(mpm_sym3_dev(tr.sigma), 1.0 / mpm_sym3_tau(tr.sigma));
      ck_assert(sym3_maxdiff(dir, dir_tr) <= 1e-12);
      ck_assert(fabs(nx.gdp - nx.g * tau / p) <= 1e-12 * nx.gdp);
      ck_assert(fabs(nx.gdp - (tau_tr - tau) / (par.G * dt)) <= 1e-9 * nx.gdp);
      ck_assert_msg(fabs(mpm_mat3_det(&nx.Fp) - 1.0) <= 1e-12, "step %d: det Fp - 1 = %g", n,
                    mpm_mat3_det(&nx.Fp) - 1.0);
      mpm_sym3 back = mpm_material_hyper_stress(&par, &nx.F, &nx.Fp);
      ck_assert_msg(sym3_maxdiff(back, nx.sigma) <= tol, "step %d: stored state off by %g", n,
                    sym3_maxdiff(back, nx.sigma));
      plastic += tau < 0.99 * tau_tr;
      pt = nx;
    }
    ck_assert_int_eq(plastic, 2000);
  }
}
END_TEST

/* The local limit: with lap = 0 and the point's own p, steady simple shear
 * (L = 10/s e_x e_y, 2000 steps of 1e-4 s, shear strain 2) settles where
 * g_{n+1} = g_n, at which the local solve gives F(mu) = -b I:
 * mu = mu(I) = mu_s + Delta_mu / (I0/I + 1) for the [DK-silo] form and
 * mu = mu_s + b I for the [HS21] form, I = gdot_p d sqrt(rho_s / p) with the
 * Mandel p = J p_cauchy (mu = tau/p is the same for Mandel and Cauchy). The
 * transient decays geometrically (1e-9 after 500 steps, round-off after
 * 1000), so 1e-11 relative leaves room for the round-off of tau and p
 * (~1e-13 relative at elastic strains ~1e-2). gdot_p carries nearly all the
 * shear rate sqrt(2 D0:D0) = 10/s. */
START_TEST(t_steady_shear_local)
{
  for (int form = 0; form < 2; form++) {
    const mpm_material_params par = params(form);
    mpm_mat3 I = mpm_mat3_identity();
    mpm_mat3 F0 = {{{0.995, 0, 0}, {0, 0.995, 0}, {0, 0, 0.995}}};
    mpm_material_hyper_point pt = hpoint(F0, I, mpm_material_hyper_stress(&par, &F0, &I),
                                         2000.0, 50.0, 0.0);
    mpm_mat3 L = {{{0, 10.0, 0}, {0, 0, 0}, {0, 0, 0}}};
    for (int n = 0; n < 2000; n++)
      pt = mpm_material_hyper_step(&par, &L, 1e-4, pt);
    double J = mpm_mat3_det(&pt.F), p = J * mpm_sym3_pressure(pt.sigma);
    double mu = mpm_sym3_tau(pt.sigma) / mpm_sym3_pressure(pt.sigma);
    double In = pt.gdp * par.d * sqrt(par.rho_s / p);
    double ref = form == MPM_NGF_DK ? par.mu_s + par.dmu / (par.I0 / In + 1.0)
                                    : par.mu_s + par.b * In;
    ck_assert_msg(fabs(mu - ref) <= 1e-11 * ref, "form %d: mu %.15g, local law %.15g", form,
                  mu, ref);
    ck_assert(pt.gdp > 9.99 && pt.gdp < 10.0);
  }
}
END_TEST

/* State decisions. Tension (p <= 0) and rho < rho_c: sigma = 0, g = 0,
 * gdot_p = sqrt(2 D0:D0), Fp = F_{n+1} exactly (Fe = I); the next step under
 * compression starts from Fe = I + dt L and reconnects with
 * g = sqrt(2 D0:D0) / mu_2 (to 4 eps: one square root and a division) and
 * tau = tau_tr p / (p + G dt g); an inverted F gives a NaN stress. */
START_TEST(t_states)
{
  const mpm_material_params par = params(MPM_NGF_DK);
  const double dt = 1e-4;
  mpm_mat3 I = mpm_mat3_identity();
  mpm_mat3 Lt = {{{100.0, 3.0, 0}, {0, 100.0, 0}, {0, 0, 100.0}}};   /* expansion */
  unsigned long s = 8u;
  mpm_material_hyper_point pt = dense_state(&par, &s, 10.0, 0.0);
  mpm_material_hyper_point a = mpm_material_hyper_step(&par, &Lt, dt, pt);
  mpm_sym3 D0 = mpm_sym3_dev(mpm_mat3_sym(&Lt));
  double gfree = sqrt(2.0 * mpm_sym3_ddot(D0, D0));
  ck_assert_int_eq(a.state, MPM_STATE_DISCONNECTED);
  ck_assert(sym3_maxabs(a.sigma) == 0.0 && a.g == 0.0);
  ck_assert(mat3_maxdiff(&a.Fp, &a.F) == 0.0);
  ck_assert(fabs(a.gdp - gfree) <= 4.0 * EPS * gfree);
  /* low density, compressed: stress-free all the same */
  mpm_material_hyper_point lo = pt;
  lo.rho = 1499.0;
  mpm_mat3 L0 = {{{0.0}}};
  mpm_material_hyper_point b = mpm_material_hyper_step(&par, &L0, dt, lo);
  ck_assert_int_eq(b.state, MPM_STATE_DISCONNECTED);
  ck_assert(sym3_maxabs(b.sigma) == 0.0 && mat3_maxdiff(&b.Fp, &b.F) == 0.0);
  /* reconnection under compression and shear */
  mpm_mat3 Lc = {{{-20.0, 30.0, 0}, {0, -20.0, 0}, {5.0, 0, -20.0}}};
  mpm_material_hyper_point c = mpm_material_hyper_step(&par, &Lc, dt, a);
  mpm_sym3 Dc0 = mpm_sym3_dev(mpm_mat3_sym(&Lc));
  double gc = sqrt(2.0 * mpm_sym3_ddot(Dc0, Dc0)) / par.mu_2;
  ck_assert_int_eq(c.state, MPM_STATE_DENSE);
  ck_assert_msg(fabs(c.g - gc) <= 4.0 * EPS * gc, "g %.17g, expected %.17g", c.g, gc);
  ck_assert(mpm_sym3_pressure(c.sigma) > 0.0);
  mpm_material_hyper_point ce = mpm_material_hyper_elastic_step(&par, &Lc, dt, a);
  double J = mpm_mat3_det(&c.F), p = J * mpm_sym3_pressure(ce.sigma);
  double tau_tr = J * mpm_sym3_tau(ce.sigma);
  ck_assert(fabs(J * mpm_sym3_tau(c.sigma) - tau_tr * p / (p + par.G * dt * c.g))
            <= 1e-12 * tau_tr);
  /* Fe = (I + dt Lc) a.F a.Fp^-1 = I + dt Lc: the stress of that stretch */
  mpm_mat3 Fe = mpm_mat3_identity();
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      Fe.m[i][j] += dt * Lc.m[i][j];
  mpm_sym3 se = mpm_material_hyper_stress(&par, &Fe, &I);
  ck_assert(sym3_maxdiff(mpm_sym3_scale(ce.sigma, J), mpm_sym3_scale(se, mpm_mat3_det(&Fe)))
            <= stress_tol(&par));
  /* inverted */
  mpm_mat3 Finv = {{{-1.0, 0, 0}, {0, 1.0, 0}, {0, 0, 1.0}}};
  mpm_material_hyper_point inv = hpoint(Finv, I, mpm_sym3_zero(), 2000.0, 0.0, 0.0);
  ck_assert(isnan(mpm_material_hyper_step(&par, &L0, dt, inv).sigma.xx));
  ck_assert(isnan(mpm_material_hyper_elastic_step(&par, &L0, dt, inv).sigma.xx));
}
END_TEST

/* The same bits, or both NaN (a NaN's payload may depend on the order of
 * the operands, which the compiler is free to swap). */
static int same_or_nan(double a, double b)
{
  return !memcmp(&a, &b, sizeof a) || (isnan(a) && isnan(b));
}

/* One point of kind k for the batch test: F, Fp, sigma_n, rho, g of every
 * state the update meets (dim 2: in the plane, no out-of-plane shear). */
static mpm_material_hyper_point batch_point(const mpm_material_params *par, unsigned long *s,
                                            int k, int dim)
{
  const mpm_mat3 I = mpm_mat3_identity();
  mpm_mat3 F = I, Fp = I, R = dim == 3 ? rand_rotation(s) : rotation(0.0, 0.0, 1.0, PI * lcg(s));
  mpm_mat3 X = rand_mat(s, 1.0);
  if (dim == 2)
    X.m[0][2] = X.m[1][2] = X.m[2][0] = X.m[2][1] = 0.0;
  double rho = 2000.0, g = 30.0 * lcg(s);
  switch (k) {
  case 0:                                                         /* generic */
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++)
        F.m[i][j] = (i == j ? 0.98 : 0.0) + 0.02 * X.m[i][j];
    F = mpm_mat3_mul(&R, &F);
    break;
  case 1:                                                         /* near the identity */
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++)
        F.m[i][j] = (i == j ? 1.0 : 0.0) - 1e-7 * fabs(X.m[i][j]);
    F = mpm_mat3_mul(&R, &F);
    break;
  case 2:                                                         /* isotropic compression */
    for (int i = 0; i < 3; i++)
      F.m[i][i] = 0.995;
    break;
  case 3: {                                                       /* turned by 180 degrees */
    const mpm_mat3 Q = dim == 3 ? rotation(X.m[0][0], X.m[1][1], X.m[2][2] + 2.0, PI)
                                : rotation(0.0, 0.0, 1.0, PI);
    for (int i = 0; i < 3; i++)
      F.m[i][i] = 0.99 + 0.002 * X.m[i][i];
    F = mpm_mat3_mul(&Q, &F);
    break;
  }
  case 4:                                                         /* tension: stress-free */
    for (int i = 0; i < 3; i++)
      F.m[i][i] = 1.01;
    break;
  case 5:                                                         /* below rho_c */
    F = mpm_mat3_mul(&R, &F);
    for (int i = 0; i < 3; i++)
      F.m[i][i] *= 0.99;
    rho = 0.9 * par->rho_c;
    break;
  case 6:                                                         /* inverted */
    F.m[0][0] = -0.99;
    break;
  default:                                                        /* not a number */
    F.m[1][0] = NAN;
    break;
  }
  if (k <= 3) {                                                   /* plastic strain too */
    mpm_sym3 a = mpm_sym3_dev(rand_sym(s, 0.02));
    if (dim == 2)
      a.yz = a.zx = 0.0;
    Fp = mpm_sym3_full(mpm_material_hyper_exp(a));
    F = mpm_mat3_mul(&F, &Fp);
  }
  mpm_sym3 sig = k == 6 || k == 7 ? mpm_sym3_zero() : mpm_material_hyper_stress(par, &F, &Fp);
  if (k <= 3 && lcg(s) < 0.25)
    sig = mpm_sym3_zero();                                        /* reconnecting */
  mpm_material_hyper_point pt = hpoint(F, Fp, sig, rho, g, 1e4 * sym_rand(s));
  pt.isp = lcg(s) < 0.5 ? 0.0 : 0.02 * lcg(s);
  return pt;
}

/* The batch update (mpm_material_ngf_hyper.update: blocks of 64 points,
 * every pass a loop over a block, the Jacobi points not converged after
 * three sweeps packed and swept again) gives each point what its point
 * update gives (update_point: the block of one), bit for bit (or NaN for
 * NaN), for 150 points (two full blocks and a partial one) in 3D and in
 * the plane, two substeps, of every kind the update meets: generic F (about
 * half need a fourth sweep), near the identity, isotropic compression (a
 * triple eigenvalue), turned by 180 degrees, reconnecting (sigma_n = 0),
 * tension and low density (stress-free), inverted (det F < 0), NaN. */
START_TEST(t_batch_is_point)
{
  enum { N = 150, NSUB = 2 };
  const mpm_material_params par = params(MPM_NGF_DK);
  const double dt = 1e-4;
  for (int dim = 2; dim <= 3; dim++) {
    unsigned long s = 31u + (unsigned long)dim;
    double L[9][N], rho[N], lap[N], isp[N], sig[6][N], g[N], gdp[N], F[9][N], Fp[9][N];
    int state[N];
    mpm_mpoint pt[N];
    mpm_mdeform def[N];
    mpm_mat3 Lm[N];
    for (int q = 0; q < N; q++) {
      const mpm_material_hyper_point h = batch_point(&par, &s, q % 8, dim);
      mpm_mat3 l = {{{0.0}}};
      for (int i = 0; i < dim; i++)
        for (int j = 0; j < dim; j++)
          l.m[i][j] = 20.0 * sym_rand(&s);
      Lm[q] = l;
      for (int i = 0; i < dim; i++)
        for (int j = 0; j < dim; j++)
          L[dim * i + j][q] = l.m[i][j];
      pt[q] = (mpm_mpoint){.sigma = h.sigma, .rho = h.rho, .g = h.g, .lap = h.lap, .isp = h.isp,
                           .gdp = 0.0, .state = MPM_STATE_DENSE};
      def[q] = (mpm_mdeform){.F = h.F, .Fp = h.Fp};
      const double sv[6] = {h.sigma.xx, h.sigma.yy, h.sigma.zz, h.sigma.xy, h.sigma.yz, h.sigma.zx};
      for (int k = 0; k < 6; k++)
        sig[k][q] = sv[k];
      rho[q] = h.rho;
      lap[q] = h.lap;
      isp[q] = h.isp;
      g[q] = h.g;
      gdp[q] = 0.0;
      state[q] = MPM_STATE_DENSE;
      for (int e = 0; e < 9; e++) {
        F[e][q] = h.F.m[e / 3][e % 3];
        Fp[e][q] = h.Fp.m[e / 3][e % 3];
      }
    }
    mpm_material_batch b = {.n = N, .dim = dim, .rho = rho, .lap = lap, .isp = isp, .g = g,
                            .gdp = gdp, .state = state};
    for (int k = 0; k < dim * dim; k++)
      b.L[k] = L[k];
    for (int k = 0; k < (dim == 3 ? 6 : 4); k++)
      b.sig[k] = sig[k];
    for (int e = 0; e < 9; e++) {
      b.F[e] = F[e];
      b.Fp[e] = Fp[e];
    }
    mpm_material_ngf_hyper.update(&par, dt, NSUB, &b);
    int dense = 0, free = 0;
    for (int q = 0; q < N; q++) {
      for (int k = 0; k < NSUB; k++)
        mpm_material_ngf_hyper.update_point(&par, &Lm[q], dt, &pt[q], &def[q]);
      const double sv[6] = {pt[q].sigma.xx, pt[q].sigma.yy, pt[q].sigma.zz, pt[q].sigma.xy,
                            pt[q].sigma.yz, pt[q].sigma.zx};
      for (int k = 0; k < (dim == 3 ? 6 : 4); k++)
        ck_assert_msg(same_or_nan(sv[k], sig[k][q]), "%dD point %d (kind %d): sigma %d %.17g, "
                      "batch %.17g", dim, q, q % 8, k, sv[k], sig[k][q]);
      ck_assert_msg(same_or_nan(pt[q].g, g[q]) && same_or_nan(pt[q].gdp, gdp[q]) &&
                    pt[q].state == state[q], "%dD point %d: g, gdot_p or state", dim, q);
      for (int e = 0; e < 9; e++)
        ck_assert_msg(same_or_nan(def[q].F.m[e / 3][e % 3], F[e][q]) &&
                      same_or_nan(def[q].Fp.m[e / 3][e % 3], Fp[e][q]),
                      "%dD point %d (kind %d): F or Fp entry %d", dim, q, q % 8, e);
      dense += state[q] == MPM_STATE_DENSE && g[q] > 0.0 && isfinite(sig[0][q]);
      free += state[q] == MPM_STATE_DISCONNECTED;
    }
    ck_assert_int_ge(dense, N / 4);                /* the kinds are met, not all one state */
    ck_assert_int_ge(free, N / 8);
  }
}
END_TEST

int main(void)
{
  Suite *s = suite_create("hyper");
  TCase *tc = tcase_create("hyper");
  tcase_set_timeout(tc, 120);
  tcase_add_test(tc, t_mat3_helpers);
  tcase_add_test(tc, t_eigen);
  tcase_add_test(tc, t_eigen_kinds);
  tcase_add_test(tc, t_polar);
  tcase_add_test(tc, t_log_exp);
  tcase_add_test(tc, t_log1p_exp);
  tcase_add_test(tc, t_uniaxial_hencky);
  tcase_add_test(tc, t_F_of_stress);
  tcase_add_test(tc, t_objectivity);
  tcase_add_test(tc, t_F_update_order);
  tcase_add_test(tc, t_rate_independence);
  tcase_add_test(tc, t_plastic_return);
  tcase_add_test(tc, t_steady_shear_local);
  tcase_add_test(tc, t_states);
  tcase_add_test(tc, t_batch_is_point);
  suite_add_tcase(s, tc);
  SRunner *sr = srunner_create(s);
  srunner_run_all(sr, CK_NORMAL);
  int nf = srunner_ntests_failed(sr);
  srunner_free(sr);
  return nf ? EXIT_FAILURE : EXIT_SUCCESS;
}
