/* hyper.c: the hyperelastic trans-phase nonlocal granular fluidity point
 * update of [HS21] §3, Algorithm 1 (MODEL.md section 7), with the local
 * fluidity solve of MODEL.md section 5 step 4 (ngf.c) reused as it is.
 *
 * One step dt with L (L_ij = d v_i / d x_j) fixed, per point:
 *   F_{n+1} = (I + dt L) F_n,  J = det F_{n+1},  Fe_tr = F_{n+1} Fp_n^-1 = Re Ue,
 *   Ee = ln Ue,  Me_tr = 2G dev(Ee) + K tr(Ee) I,  p = -tr(Me_tr)/3 = -K tr(Ee),
 *   tau_tr = |dev Me_tr| / sqrt(2)  (the tau of mpm_sym3_tau),
 *   Np = dev(Me_tr) / |dev Me_tr|.
 * States:
 *   rho_{n+1} < rho_c or p <= 0: stress-free, sigma = 0, g = 0,
 *     gdot_p = sqrt(2 D0:D0) (as the 2D models), Fp_{n+1} = F_{n+1};
 *   p_n <= 0 (stress-free before, now dense): g = sqrt(2 D0:D0) / mu_2  [HS21 eq. 23];
 *   p_n > 0: g* = max(0, g_n + (dt/t0) A^2 d^2 lap), g = the root of the
 *     section 5 quadratic with p, tau_tr, g*, mu_n g_n
 *     (mpm_material_ngf_gstar, mpm_material_ngf_fluidity; [HS21] eq. 24 is its
 *     explicit cousin, the semi-implicit form is the one of the 2D code);
 *   then tau = tau_tr p / (p + G dt g),  Me = Me_tr - sqrt(2) (tau_tr - tau) Np,
 *   sigma = J^-1 Re Me Re^T,  gdot_p = g tau / p = (tau_tr - tau) / (G dt),
 *   Lp = gdot_p Np / sqrt(2),  Fp_{n+1} = exp(dt Lp) Fp_n          [eq. 25-31].
 *
 * Choices, where MODEL.md section 7 or [HS21] leave room or read otherwise:
 * - F_{n+1} = (I + dt L) F_n: dF/dt = L F for the spatial gradient L of this
 *   code. MODEL.md and [HS21] eq. 18 write F_n (I + dt L), which is the same
 *   update for the transposed gradient (L_ij = d v_j / d x_i); with this
 *   code's L it would stretch a body that has turned along its material axes
 *   instead of the spatial ones (tests/test_hyper.c, t_F_update_order).
 * - Fp_{n+1} = exp(dt Lp) Fp_n: Lp = dFp/dt Fp^-1 lives, with Me and Np, in
 *   the intermediate configuration. Then Fe_{n+1} = Fe_tr exp(-dt Lp), and
 *   since Np is coaxial with Ue_tr (Me_tr is an isotropic function of Ee),
 *   Re is unchanged and Ee_{n+1} = Ee_tr - dt Lp exactly: the stored state
 *   (F, Fp) gives back the returned Me, so nothing drifts from step to step.
 *   The exponential instead of I + dt Lp ([HS21] eq. 31, MODEL.md) keeps
 *   det Fp = exp(dt tr Lp) det Fp_n = det Fp_n, tr Np = 0 (plastic flow is
 *   isochoric); the forward-Euler factor would change det Fp by O(dt^2).
 * - gdot_p = g tau / p, the friction mu_{n+1} = tau/p of the return, also in
 *   the step that reconnects ([HS21] uses mu_2 there): the plastic flow is
 *   then exactly the deviatoric stress removed, G dt gdot_p = tau_tr - tau,
 *   which the consistency above needs.
 * - The reconnecting fluidity uses the deviatoric rate, sqrt(2 D0:D0) / mu_2
 *   ([HS21] writes sqrt(2)|D|; equal for isochoric D): plastic flow is
 *   isochoric, and sqrt(2 D0:D0) is the gdot_p of a stress-free point
 *   (mpm_material_mu_i_gdp), so gdot_p = g mu_2 is continuous across
 *   reconnection as in the 2D models.
 * - Stress-free points take Fp_{n+1} = F_{n+1} ([HS21] Algorithm 1), i.e.
 *   Fe = I: a grain that separates keeps no elastic strain, and when it is
 *   caught again it starts from its stress-free natural state instead of the
 *   stretched one it left. Fp then carries the volume change (det Fp = J at
 *   the last separation), and sigma divides Re Me Re^T by J = det F as
 *   [HS21] eq. 27.
 * - det F <= 0 (an inverted point, or non-finite F) gives a NaN stress, a
 *   physical failure for the caller to report, never a stress-free state.
 *
 * Eigen-decomposition, logarithm and polar decomposition. Everything is
 * computed from the eigenpairs (mu_i, v_i) of C - I = Fe^T Fe - I, formed
 * from H = Fe - I as H + H^T + H^T H, by cyclic Jacobi rotations:
 *   Ue = V diag(sqrt(1 + mu)) V^T,  Ee = V diag(log1p(mu)/2) V^T,
 *   Re V = Fe V diag(1 / sqrt(1 + mu))  (Re = Fe Ue^-1, never formed alone).
 * Why this route: (1) C does not see the rotation (R^T R = I), so a rotation
 * of any size, 179 or 180 degrees included, costs no accuracy, unlike
 * rotation-angle formulas; (2) Fe is near a rotation in granular flow (small
 * elastic strain), where C - I is small: taken from H instead of C, and with
 * log1p, the strain keeps its relative accuracy as it goes to zero, and
 * (3) Jacobi rotations give eigenvectors orthonormal to round-off even for
 * equal or nearly equal eigenvalues (the near-identity case), where the
 * closed-form (trigonometric) 3x3 eigenvalues lose accuracy and the
 * eigenvectors from cross products break down; the cyclic method converges
 * quadratically, a few sweeps for 3x3. A Higham (Newton) polar iteration
 * would give Re well, but the Hencky strain needs the eigenvectors anyway.
 * The cost: C squares the condition number, so Re is orthogonal to about
 * eps cond(Fe)^2, which for elastic stretches of a few percent is eps.
 *
 * The sweeps. A sweep rotates in the planes (0,1), (0,2), (1,2) in turn,
 * every nonzero a_pq (a zero one is the rotation by t = 0, an exact no-op,
 * so the zeros of plane strain stay zeros), and the sweeps stop after the
 * first that leaves every a_pq below eps/2 of the geometric mean of a_pp
 * and a_qq: then the diagonal is the spectrum to round-off relative to each
 * entry, graded matrices included. Rotating an a_pq that is already that
 * small does no harm: it moves the diagonal by a_pq^2 / |a_qq - a_pp|
 * (below eps^2 of the entries) or, when the two are equal to round-off,
 * turns a pair that is degenerate to round-off. Cyclic Jacobi converges
 * quadratically (off_{k+1} ~ off_k^2 / gap; clusters of equal eigenvalues
 * do not slow it). Measured on 200,000 matrices of each kind, the largest
 * |a_pq| / max|a| left after sweeps 1, 2, 3, 4 is 0.9, 0.15, 3e-5, 2e-16 for
 * random entries and likewise for C - I of R (I + e X), e from 1e-2 to
 * 1e-12; 3e-2, 6e-5, 7e-11, 2e-16 for two eigenvalues 1e-3 apart
 * (relative); 5e-4, 1e-4, 1e-8, 1e-16 for three 1e-3 apart; 2e-3, 8e-7,
 * 3e-19 for the graded 1, 1e-8, 1e-16. Four sweeps converge every one;
 * three converge 49 % of the random matrices, 61 % of the C - I, 84 to
 * 100 % of the nearly degenerate and graded ones and 98 % of the C - I of
 * the 3D silo (silo3d-hyper, its first 200 steps). So the eigen pass runs
 * three sweeps over all the points of a block and then sweeps only the
 * points not converged yet, packed (block_eigen). V is a product of
 * rotations, each orthogonal to round-off, so it is orthonormal to a few
 * eps whatever the eigenvalues: over all those matrices |A V - V L| is
 * below 6 eps |A| and |V^T V - I| below 4 eps.
 *
 * The batch update runs on blocks of HYPER_BLOCK points held as arrays, a
 * pass at a time: F_{n+1}; Fe_tr and C - I; the eigenpairs; the principal
 * logarithms, invariants and state decision; the fluidity solve of ngf.c,
 * point by point; the return and the stress; Fp. Every pass but the
 * fluidity solve is a loop that vectorises (no library call: ln(1 + x) and
 * exp(x) are written out below).
 * One point (mpm_material_hyper_step and the other point functions, the
 * table's update_point) is the block of one, so the batch gives the point
 * update bit for bit. */
#include "material/hyper.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "core/points.h"
#include "material/hyper_math.h"

enum {
  HYPER_BLOCK = 64,          /* points per block of the batch update (a step's chunk) */
  JACOBI_VECTOR_SWEEPS = 3,  /* sweeps over all points of a block (see above) */
  JACOBI_SWEEPS = 32         /* 4 in every case measured; the cap only bounds a bad input */
};

double mpm_material_hyper_log1p(double x)
{
  return hyper_log1p(x);
}

double mpm_material_hyper_exp_scalar(double x)
{
  return hyper_exp(x);
}

/* ---- a block of points ------------------------------------------------------ */

/* The points of a batch as the passes see them, n values behind each
 * pointer: every entry of L, F, Fp and of the stress (the entries the plane
 * does not have, and absent lap, isp, point to zeros; the stress the plane
 * does not keep is written to a sink). */
typedef struct hyper_view {
  const double *L[9];            /* L_ij at [3 i + j] */
  const double *rho, *lap, *isp;
  const double *sig_in[6];       /* sigma_n (xx yy zz xy yz zx) */
  double *sig_out[6];            /* sigma_{n+1} */
  double *g, *gdp;
  int *state;
  double *F[9], *Fp[9];          /* F_ij, Fp_ij at [3 i + j]: in at t_n, out at t_{n+1} */
} hyper_view;

/* What the last passes do with a point's stress, g and Fp. */
enum hyper_mode {
  HYPER_RETURN = 0,   /* sigma = J^-1 Re Me Re^T, Fp_{n+1} = exp(dt Lp) Fp_n */
  HYPER_FREE,         /* stress-free: sigma = 0, Fp_{n+1} = F_{n+1} */
  HYPER_KEEP          /* elastic (or det F <= 0): sigma of Me_tr, Fp kept */
};

/* Per-point intermediates of a block of up to HYPER_BLOCK points, each an
 * array over the block (all double, flags too: an int array in a loop of
 * doubles would make it take 8 points at a time, in twice the registers). */
typedef struct hyper_block {
  double fe[9][HYPER_BLOCK];   /* Fe_tr = F_{n+1} Fp_n^-1, row-major */
  double a[6][HYPER_BLOCK];    /* C - I (xx yy zz xy yz zx); after block_eigen its
                                  diagonal holds the eigenvalues mu_i */
  double v[9][HYPER_BLOCK];    /* V, row-major: the principal directions of Ue */
  double e[3][HYPER_BLOCK];    /* dev(Ee), principal */
  double J[HYPER_BLOCK];       /* det F_{n+1} */
  double p[HYPER_BLOCK];       /* p = -K tr(Ee) */
  double tau[HYPER_BLOCK];     /* tau_tr = |dev Me_tr| / sqrt(2) */
  double gn[HYPER_BLOCK];      /* g_n (0 for a point stress-free at t_n) */
  double mug[HYPER_BLOCK];     /* mu_n g_n */
  double pn[HYPER_BLOCK];      /* p_n = -tr(sigma_n)/3 */
  double gfree[HYPER_BLOCK];   /* sqrt(2 D0:D0) */
  double g[HYPER_BLOCK];       /* g_{n+1} */
  double solve[HYPER_BLOCK];   /* 1: g_{n+1} from the local fluidity solve, else 0 */
  double w[HYPER_BLOCK];       /* dt Lp = w dev(Ee) (1 - r for a return, else 0) */
  double mode[HYPER_BLOCK];    /* enum hyper_mode */
  double more[HYPER_BLOCK];    /* 1: Jacobi not converged yet, else 0 */
  double ca[6][HYPER_BLOCK];   /* the matrices not converged after the first sweeps, */
  double cv[9][HYPER_BLOCK];   /* their V */
  double cmore[HYPER_BLOCK];   /* and flags, packed; */
  size_t idx[HYPER_BLOCK];     /* their points */
  double zero[HYPER_BLOCK];    /* zeros: absent inputs */
  double sink[2][HYPER_BLOCK]; /* the plane's yz, zx out */
} hyper_block;

/* C - I = H + H^T + H^T H of f = I + H (h = f - I, exact near I). */
HYPER_INLINE void c_minus_i(const mpm_mat3 *f, double c[6])
{
  mpm_mat3 h = *f;
  for (int i = 0; i < 3; i++)
    h.m[i][i] -= 1.0;                                              /* h = f - I */
  const int ij[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {0, 2}};
  for (int k = 0; k < 6; k++) {
    const int i = ij[k][0], j = ij[k][1];
    const double hh = h.m[0][i] * h.m[0][j] + h.m[1][i] * h.m[1][j] + h.m[2][i] * h.m[2][j];
    c[k] = h.m[i][j] + h.m[j][i] + hh;                             /* (h + h^T + h^T h)_ij */
  }
}

/* a diag(d) a^T for a general a (the congruence of a diagonal). */
HYPER_INLINE mpm_sym3 congruence_diag(const mpm_mat3 *a, const double d[3])
{
  mpm_mat3 P;
#pragma GCC unroll 3
  for (int i = 0; i < 3; i++)
#pragma GCC unroll 3
    for (int k = 0; k < 3; k++)
      P.m[i][k] = a->m[i][k] * d[k];                               /* P = a diag(d) */
  double c[3][3];
#pragma GCC unroll 3
  for (int i = 0; i < 3; i++)
#pragma GCC unroll 3
    for (int j = i; j < 3; j++)
      c[i][j] = P.m[i][0] * a->m[j][0] + P.m[i][1] * a->m[j][1] + P.m[i][2] * a->m[j][2];
  return (mpm_sym3){c[0][0], c[1][1], c[2][2], c[0][1], c[1][2], c[0][2]};
}

/* f v diag(d): the columns of f v scaled. */
HYPER_INLINE mpm_mat3 mul_scale_cols(const mpm_mat3 *f, const mpm_mat3 *v, const double d[3])
{
  mpm_mat3 w = mpm_mat3_mul(f, v);
#pragma GCC unroll 3
  for (int i = 0; i < 3; i++)
#pragma GCC unroll 3
    for (int j = 0; j < 3; j++)
      w.m[i][j] *= d[j];
  return w;
}

/* Pass 1 (vectorises): F_{n+1} = (I + dt L) F_n (advance; else F is
 * F_{n+1} already), J = det F_{n+1}; for the plastic step, the start of the
 * step: p_n, g_n, mu_n g_n and the gdot_p of a stress-free point,
 * sqrt(2 D0:D0) (mpm_material_free_gdp, as every model). */
HYPER_INLINE void block_advance(double dt, const hyper_view *b, size_t n, hyper_block *s,
                                int advance, int plastic)
{
  const double *L[9], *sig[6];
  double *F[9];
  for (int e = 0; e < 9; e++) {
    L[e] = b->L[e];
    F[e] = b->F[e];
  }
  for (int k = 0; k < 6; k++)
    sig[k] = b->sig_in[k];
  const double *g = b->g;
  HYPER_IVDEP
  for (size_t q = 0; q < n; q++) {
    mpm_mat3 f, l;
    for (int e = 0; e < 9; e++) {
      f.m[e / 3][e % 3] = F[e][q];
      l.m[e / 3][e % 3] = L[e][q];
    }
    if (advance) {
      mpm_mat3 A = mpm_mat3_identity();
      for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
          A.m[i][j] += dt * l.m[i][j];
      f = mpm_mat3_mul(&A, &f);                                    /* F_{n+1} = (I + dt L) F_n */
      for (int e = 0; e < 9; e++)
        F[e][q] = f.m[e / 3][e % 3];
    }
    s->J[q] = mpm_mat3_det(&f);
    if (plastic) {
      const mpm_sym3 sn = {sig[0][q], sig[1][q], sig[2][q], sig[3][q], sig[4][q], sig[5][q]};
      const double p_n = mpm_sym3_pressure(sn);
      const int was_dense = p_n > 0.0;
      const double g_n = was_dense ? g[q] : 0.0;
      s->gn[q] = g_n;
      s->pn[q] = p_n;
      s->mug[q] = was_dense ? g_n * mpm_sym3_tau(sn) / p_n : 0.0;  /* mu_n g_n */
      s->gfree[q] = mpm_material_free_gdp(mpm_mat3_sym(&l));        /* sqrt(2 D0:D0) */
    }
  }
}

/* Pass 2 (vectorises): Fe_tr = F_{n+1} Fp_n^-1 and C - I. */
HYPER_INLINE void block_trial(const hyper_view *b, size_t n, hyper_block *s)
{
  const double *F[9], *Fp[9];
  for (int e = 0; e < 9; e++) {
    F[e] = b->F[e];
    Fp[e] = b->Fp[e];
  }
  HYPER_IVDEP
  for (size_t q = 0; q < n; q++) {
    mpm_mat3 f, fp;
    for (int e = 0; e < 9; e++) {
      f.m[e / 3][e % 3] = F[e][q];
      fp.m[e / 3][e % 3] = Fp[e][q];
    }
    const mpm_mat3 fpi = mpm_mat3_inverse(&fp);
    const mpm_mat3 fe = mpm_mat3_mul(&f, &fpi);                    /* Fe_tr = F Fp^-1 */
    for (int e = 0; e < 9; e++)
      s->fe[e][q] = fe.m[e / 3][e % 3];
    double c[6];
    c_minus_i(&fe, c);
    for (int k = 0; k < 6; k++)
      s->a[k][q] = c[k];
  }
}

/* sweeps cyclic sweeps of the first n matrices of s->a (first) or of the
 * packed s->ca (destroyed), their rotations accumulated into s->v or s->cv
 * (first: v = I on entry, set here); then more = 0 where the matrix has
 * converged (or, after the first sweeps, is not finite: no sweep helps),
 * else 1. A loop that vectorises. */
HYPER_INLINE void jacobi_pass(size_t n, hyper_block *s, int sweeps, int first)
{
  double(*a)[HYPER_BLOCK] = first ? s->a : s->ca, (*v)[HYPER_BLOCK] = first ? s->v : s->cv;
  double *more = first ? s->more : s->cmore;
  HYPER_IVDEP
  for (size_t q = 0; q < n; q++) {
    double w[6], u[9] = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
    for (int k = 0; k < 6; k++)
      w[k] = a[k][q];
    if (!first)
      for (int k = 0; k < 9; k++)
        u[k] = v[k][q];
    jacobi_sweep(w, u, first);
#pragma GCC unroll 4
    for (int sweep = 1; sweep < sweeps; sweep++)
      jacobi_sweep(w, u, 0);
    for (int k = 0; k < 6; k++)
      a[k][q] = w[k];
    for (int k = 0; k < 9; k++)
      v[k][q] = u[k];
    const int done = jacobi_converged(w) || (!first && !isfinite(w[0] + w[1] + w[2]));
    more[q] = done ? 0.0 : 1.0;
  }
}

/* Pass 3: the eigenpairs of the block's a (destroyed): a = v diag(mu) v^T, mu
 * on the diagonal of a, by cyclic sweeps until every a_pq is negligible:
 * JACOBI_VECTOR_SWEEPS sweeps over all points at once, then sweeps over the
 * points not converged yet, packed (at most JACOBI_SWEEPS in all). Every
 * loop over points vectorises, and what a point gets depends on it alone,
 * not on its block. */
HYPER_NOINLINE void block_eigen(size_t n, hyper_block *s)
{
  jacobi_pass(n, s, JACOBI_VECTOR_SWEEPS, 1);
  size_t m = 0;
  for (size_t q = 0; q < n; q++) {
    if (s->more[q] == 0.0)
      continue;
    for (int k = 0; k < 6; k++)
      s->ca[k][m] = s->a[k][q];
    for (int k = 0; k < 9; k++)
      s->cv[k][m] = s->v[k][q];
    s->idx[m++] = q;
  }
  for (int sweep = JACOBI_VECTOR_SWEEPS; m > 0; sweep++) {
    jacobi_pass(m, s, 1, 0);
    const int last = sweep + 1 >= JACOBI_SWEEPS;
    size_t kept = 0;
    for (size_t j = 0; j < m; j++) {
      if (s->cmore[j] == 0.0 || last) {                            /* done: back to its point */
        const size_t q = s->idx[j];
        for (int k = 0; k < 6; k++)
          s->a[k][q] = s->ca[k][j];
        for (int k = 0; k < 9; k++)
          s->v[k][q] = s->cv[k][j];
        continue;
      }
      for (int k = 0; k < 6; k++)                                  /* not yet: packed again */
        s->ca[k][kept] = s->ca[k][j];
      for (int k = 0; k < 9; k++)
        s->cv[k][kept] = s->cv[k][j];
      s->idx[kept++] = s->idx[j];
    }
    m = kept;
  }
}

/* Pass 4 (vectorises): Ee_i = ln sqrt(1 + mu_i) principal, dev(Ee),
 * p = -K tr(Ee), tau_tr = |2G dev(Ee)| / sqrt(2); for the plastic step the
 * state decision: det F <= 0, a failure (mode keep: the stress is NaN);
 * rho_{n+1} < rho_c or p <= 0, stress-free; else the return, with
 * g = sqrt(2 D0:D0) / mu_2 for a point that reconnects ([HS21] eq. 23) or
 * the fluidity solve of the next pass (solve = 1). */
HYPER_INLINE void block_invariants(const mpm_material_params *par, const hyper_view *b,
                                   size_t n, hyper_block *s, int plastic)
{
  const double G = par->G, K = par->K, rho_c = par->rho_c, mu_2 = par->mu_2;
  const double *rho = b->rho;
  for (size_t q = 0; q < n; q++) {
    double e[3];
    for (int i = 0; i < 3; i++)
      e[i] = 0.5 * hyper_log1p(s->a[i][q]);                        /* ln sqrt(1 + mu) */
    const double tr = e[0] + e[1] + e[2], m = tr / 3.0;
    double ss = 0.0;
    for (int i = 0; i < 3; i++) {
      const double e0 = e[i] - m;                                  /* dev(Ee) */
      const double s0 = 2.0 * G * e0;                              /* 2G dev(Ee) */
      s->e[i][q] = e0;
      ss += s0 * s0;
    }
    const double p = -K * tr;                                      /* -tr(Me)/3 */
    s->p[q] = p;
    s->tau[q] = sqrt(0.5 * ss);                                    /* |dev Me| / sqrt(2) */
    if (plastic) {
      const int bad = !(s->J[q] > 0.0), loose = !(rho[q] >= rho_c) || !(p > 0.0);
      const double mode = bad ? HYPER_KEEP : loose ? HYPER_FREE : HYPER_RETURN;
      s->mode[q] = mode;
      s->solve[q] = mode == HYPER_RETURN && s->pn[q] > 0.0 ? 1.0 : 0.0;
      s->g[q] = s->gfree[q] / mu_2;                                /* reconnects */
    } else {
      s->mode[q] = HYPER_KEEP;
      s->solve[q] = 0.0;
      s->g[q] = 0.0;
    }
  }
}

/* Pass 5 (one point at a time: library calls): g_{n+1} of the points that
 * were dense, the root of the local NGF solve (ngf.c) with
 * g* = max(0, g_n + (dt/t0) A^2 d^2 lap); the state. */
static void block_solve(const mpm_material_params *par, double dt, const hyper_view *b,
                        size_t n, hyper_block *s, int plastic)
{
  for (size_t q = 0; q < n; q++) {
    if (s->solve[q] != 0.0) {
      const double gs = mpm_material_ngf_gstar(par, dt, s->gn[q], b->lap[q]);   /* g* */
      s->g[q] = mpm_material_ngf_fluidity(par, dt, s->p[q], s->tau[q], gs, s->mug[q],
                                          b->isp[q]);                            /* g_{n+1} */
    }
    const double mode = s->mode[q];
    b->state[q] = !plastic || mode == HYPER_RETURN ? MPM_STATE_DENSE
                : mode == HYPER_FREE               ? MPM_STATE_DISCONNECTED
                                                   : b->state[q];
  }
}

/* Pass 6 (vectorises): the return, tau / tau_tr = r = p / (p + G dt g),
 * gdot_p = g tau / p = (tau_tr - tau) / (G dt), and dt Lp = (1 - r) dev(Ee)
 * (principal values w e0_i in V: G dt gdot_p = tau_tr - tau = (1 - r) tau_tr);
 * g and gdot_p out (stress-free: 0 and sqrt(2 D0:D0); elastic: 0 and 0;
 * det F <= 0: kept). sigma_{n+1} = J^-1 Re Me Re^T with
 * Me = -p I + r dev(Me_tr) principal in V, Re V = Fe V diag(1/sqrt(1 + mu)),
 * so sigma = J^-1 (Fe V) diag(Me_i / (1 + mu_i)) (Fe V)^T (NaN if J <= 0),
 * or 0 (stress-free). */
HYPER_INLINE void block_stress(const mpm_material_params *par, double dt, const hyper_view *b,
                               size_t n, hyper_block *s, int plastic)
{
  double *sig[6];
  for (int k = 0; k < 6; k++)
    sig[k] = b->sig_out[k];
  double *g_out = b->g, *gdp_out = b->gdp;
  const mpm_material_params pl = *par;   /* a local copy: its fields load unconditionally */
  const double G2 = 2.0 * par->G, Gdt = par->G * dt;
  HYPER_IVDEP
  for (size_t q = 0; q < n; q++) {
    const double J = s->J[q], p = s->p[q], tau = s->tau[q], g = s->g[q], mode = s->mode[q];
    const int ret = mode == HYPER_RETURN;
    const double r = ret ? mpm_material_ngf_return_ratio(&pl, dt, p, g) : 1.0;  /* tau/tau_tr */
    s->w[q] = ret ? r * (Gdt * g) / p : 0.0;                       /* 1 - r, no cancellation */
    const int loose = mode == HYPER_FREE, bad = !(J > 0.0);
    if (plastic) {
      const double g_n = g_out[q], gdp_n = gdp_out[q], gfree = s->gfree[q];
      g_out[q] = ret ? g : loose ? 0.0 : g_n;
      gdp_out[q] = ret ? g * r * tau / p : loose ? gfree : gdp_n;
    } else {
      g_out[q] = 0.0;
      gdp_out[q] = 0.0;
    }
    mpm_mat3 fe, v;
#pragma GCC unroll 9
    for (int e = 0; e < 9; e++) {
      fe.m[e / 3][e % 3] = s->fe[e][q];
      v.m[e / 3][e % 3] = s->v[e][q];
    }
    double d[3];
#pragma GCC unroll 3
    for (int i = 0; i < 3; i++)                                    /* J^-1 Me_i / (1 + mu_i) */
      d[i] = (r * (G2 * s->e[i][q]) - p) / (J * (1.0 + s->a[i][q]));
    const mpm_mat3 fv = mpm_mat3_mul(&fe, &v);                     /* Fe V */
    const mpm_sym3 sc = congruence_diag(&fv, d);
    const double out[6] = {sc.xx, sc.yy, sc.zz, sc.xy, sc.yz, sc.zx};
#pragma GCC unroll 6
    for (int k = 0; k < 6; k++)
      sig[k][q] = loose ? 0.0 : bad ? NAN : out[k];
  }
}

/* Pass 7 (vectorises): Fp_{n+1} = exp(dt Lp) Fp_n, exp(dt Lp) = V diag(x) V^T
 * with x_i = exp(w dev(Ee)_i); or F_{n+1} (stress-free), or Fp_n kept. */
HYPER_INLINE void block_flow(const hyper_view *b, size_t n, hyper_block *s)
{
  const double *F[9];
  double *Fp[9];
  for (int e = 0; e < 9; e++) {
    F[e] = b->F[e];
    Fp[e] = b->Fp[e];
  }
  HYPER_IVDEP
  for (size_t q = 0; q < n; q++) {
    mpm_mat3 v, fp;
#pragma GCC unroll 9
    for (int e = 0; e < 9; e++) {
      v.m[e / 3][e % 3] = s->v[e][q];
      fp.m[e / 3][e % 3] = Fp[e][q];
    }
    const double w = s->w[q], mode = s->mode[q];
    double x[3];
#pragma GCC unroll 3
    for (int i = 0; i < 3; i++)
      x[i] = hyper_exp(w * s->e[i][q]);                            /* exp(dt Lp) principal */
    const mpm_sym3 E = congruence_diag(&v, x);                     /* exp(dt Lp) */
    const mpm_mat3 Ef = mpm_sym3_full(E), efp = mpm_mat3_mul(&Ef, &fp);
#pragma GCC unroll 9
    for (int e = 0; e < 9; e++)
      Fp[e][q] = mode == HYPER_RETURN ? efp.m[e / 3][e % 3]
               : mode == HYPER_FREE   ? F[e][q]
                                      : fp.m[e / 3][e % 3];
  }
}

/* One step dt of the block's n points of view b (see the top of the file):
 * advance = 0: F is F_{n+1} already; plastic = 0: the elastic variant. */
HYPER_INLINE void block_step(const mpm_material_params *par, double dt, const hyper_view *b,
                             size_t n, hyper_block *s, int advance, int plastic)
{
  block_advance(dt, b, n, s, advance, plastic);
  block_trial(b, n, s);
  block_eigen(n, s);
  block_invariants(par, b, n, s, plastic);
  block_solve(par, dt, b, n, s, plastic);
  block_stress(par, dt, b, n, s, plastic);
  block_flow(b, n, s);
}

/* ---- one point ---------------------------------------------------------------- */

/* The view of one point: L, its state and deformation gradients by address
 * (the block of n = 1). */
static void point_view(hyper_view *b, const mpm_mat3 *L, mpm_material_hyper_point *pt)
{
  for (int e = 0; e < 9; e++) {
    b->L[e] = &L->m[e / 3][e % 3];
    b->F[e] = &pt->F.m[e / 3][e % 3];
    b->Fp[e] = &pt->Fp.m[e / 3][e % 3];
  }
  double *sig[6] = {&pt->sigma.xx, &pt->sigma.yy, &pt->sigma.zz, &pt->sigma.xy, &pt->sigma.yz,
                    &pt->sigma.zx};
  for (int k = 0; k < 6; k++)
    b->sig_in[k] = b->sig_out[k] = sig[k];
  b->rho = &pt->rho;
  b->lap = &pt->lap;
  b->isp = &pt->isp;
  b->g = &pt->g;
  b->gdp = &pt->gdp;
  b->state = &pt->state;
}

/* The step of one point: the block step with n = 1. */
HYPER_INLINE mpm_material_hyper_point point_step(const mpm_material_params *par,
                                                 const mpm_mat3 *L, double dt,
                                                 mpm_material_hyper_point pt, int advance,
                                                 int plastic)
{
  hyper_block s;
  hyper_view b;
  point_view(&b, L, &pt);
  block_step(par, dt, &b, 1, &s, advance, plastic);
  return pt;
}

void mpm_material_hyper_eigen(mpm_sym3 a, double lam[3], mpm_mat3 *v)
{
  hyper_block s;
  const double w[6] = {a.xx, a.yy, a.zz, a.xy, a.yz, a.zx};
  for (int k = 0; k < 6; k++)
    s.a[k][0] = w[k];
  block_eigen(1, &s);
  for (int i = 0; i < 3; i++)
    lam[i] = s.a[i][0];
  for (int e = 0; e < 9; e++)
    v->m[e / 3][e % 3] = s.v[e][0];
}

mpm_sym3 mpm_material_hyper_log(mpm_sym3 a)
{
  double lam[3];
  mpm_mat3 v;
  mpm_material_hyper_eigen(mpm_sym3_add_iso(a, -1.0), lam, &v);   /* a - I = v diag(lam) v^T */
  for (int i = 0; i < 3; i++)
    lam[i] = hyper_log1p(lam[i]);                                  /* ln(1 + lam) */
  return congruence_diag(&v, lam);
}

mpm_sym3 mpm_material_hyper_exp(mpm_sym3 a)
{
  double lam[3];
  mpm_mat3 v;
  mpm_material_hyper_eigen(a, lam, &v);
  for (int i = 0; i < 3; i++)
    lam[i] = expm1(lam[i]);                                        /* exp(lam) - 1 */
  return mpm_sym3_add_iso(congruence_diag(&v, lam), 1.0);
}

void mpm_material_hyper_polar(const mpm_mat3 *f, mpm_mat3 *r, mpm_sym3 *u)
{
  hyper_block s;
  double c[6];
  c_minus_i(f, c);                                                 /* C - I */
  for (int k = 0; k < 6; k++)
    s.a[k][0] = c[k];
  block_eigen(1, &s);
  mpm_mat3 v;
  double su[3], iu[3];
  for (int e = 0; e < 9; e++)
    v.m[e / 3][e % 3] = s.v[e][0];
  for (int i = 0; i < 3; i++) {
    su[i] = sqrt(1.0 + s.a[i][0]);                                 /* principal stretches */
    iu[i] = 1.0 / su[i];
  }
  *u = congruence_diag(&v, su);                                    /* U = V diag(s) V^T */
  mpm_mat3 rv = mul_scale_cols(f, &v, iu);                         /* R V = F V diag(1/s) */
  mpm_mat3 vt = mpm_mat3_transpose(&v);
  *r = mpm_mat3_mul(&rv, &vt);                                     /* R = (R V) V^T */
}

mpm_sym3 mpm_material_hyper_stress(const mpm_material_params *par, const mpm_mat3 *F,
                                   const mpm_mat3 *Fp)
{
  const mpm_mat3 L = {{{0.0}}};
  mpm_material_hyper_point pt = {.F = *F, .Fp = *Fp};
  return point_step(par, &L, 0.0, pt, 0, 0).sigma;
}

mpm_mat3 mpm_material_hyper_F_of_stress(const mpm_material_params *par, mpm_sym3 sigma)
{
  /* Fe = Ue = exp(Ee) coaxial with sigma, Re = I: Me = J sigma, so
   * Ee = J dev(sigma) / 2G + (ln J / 3) I with J = exp(tr Ee) the root of
   * ln J = J s, s = tr(sigma) / 3K (Newton from J = 1; for compression
   * s < 0 the root is unique and Newton converges from there) */
  const double sv = mpm_sym3_trace(sigma) / (3.0 * par->K);
  double J = 1.0;
  for (int k = 0; k < 50; k++) {
    const double step = (log(J) - J * sv) / (1.0 / J - sv);
    J -= step;
    if (!(J > 0.0) || fabs(step) <= 1e-16 * J)
      break;
  }
  mpm_mat3 F;
  if (!(J > 0.0) || !isfinite(J)) {                   /* no elastic state: NaN */
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++)
        F.m[i][j] = NAN;
    return F;
  }
  const mpm_sym3 Ee = mpm_sym3_add_iso(mpm_sym3_scale(mpm_sym3_dev(sigma), J / (2.0 * par->G)),
                                       log(J) / 3.0);
  const mpm_sym3 U = mpm_material_hyper_exp(Ee);
  const double u[3][3] = {{U.xx, U.xy, U.zx}, {U.xy, U.yy, U.yz}, {U.zx, U.yz, U.zz}};
  for (int i = 0; i < 3; i++)
    for (int j = 0; j < 3; j++)
      F.m[i][j] = u[i][j];
  return F;
}

mpm_material_hyper_point mpm_material_hyper_elastic_step(const mpm_material_params *par,
                                                         const mpm_mat3 *L, double dt,
                                                         mpm_material_hyper_point pt)
{
  return point_step(par, L, dt, pt, 1, 0);
}

mpm_material_hyper_point mpm_material_hyper_step(const mpm_material_params *par,
                                                 const mpm_mat3 *L, double dt,
                                                 mpm_material_hyper_point pt)
{
  return point_step(par, L, dt, pt, 1, 1);
}

/* ---- the model -------------------------------------------------------------- */

/* The parameters of the NGF model, checked as the plane NGF checks them. */
static int ngf_hyper_check(const mpm_material_params *par, mpm_err *err)
{
  return mpm_material_ngf.check(par, err);
}

/* One point of the table's interface: the block step with n = 1, so that
 * it is the batch update of that point bit for bit. */
static void ngf_hyper_update_point(const mpm_material_params *par, const mpm_mat3 *L,
                                   double dt, mpm_mpoint *pt, mpm_mdeform *def)
{
  mpm_material_hyper_point h = {.F = def->F, .Fp = def->Fp, .sigma = pt->sigma, .rho = pt->rho,
                                .g = pt->g, .lap = pt->lap, .isp = pt->isp, .gdp = pt->gdp,
                                .state = pt->state};
  hyper_block s;
  hyper_view b;
  point_view(&b, L, &h);
  block_step(par, dt, &b, 1, &s, 1, 1);
  pt->sigma = h.sigma;
  pt->g = h.g;
  pt->gdp = h.gdp;
  pt->state = h.state;
  def->F = h.F;
  def->Fp = h.Fp;
}

/* A batch in blocks of HYPER_BLOCK points, nsub steps each, read and
 * written in place through the block's view; in the plane the absent
 * entries of L and sigma_n are zeros (sigma yz, zx zeroed each substep)
 * and sigma yz, zx out are not kept. */
static void ngf_hyper_update(const mpm_material_params *par, double dt, int nsub,
                             const mpm_material_batch *b)
{
  const int D = b->dim;
  hyper_block s;
  for (size_t q = 0; q < HYPER_BLOCK; q++)
    s.zero[q] = 0.0;
  for (size_t q0 = 0; q0 < b->n; q0 += HYPER_BLOCK) {
    const size_t n = b->n - q0 < HYPER_BLOCK ? b->n - q0 : HYPER_BLOCK;
    hyper_view v;
    for (int i = 0; i < 3; i++)
      for (int j = 0; j < 3; j++)
        v.L[3 * i + j] = i < D && j < D ? b->L[D * i + j] + q0 : s.zero;
    for (int k = 0; k < 6; k++) {
      const int kept = D == 3 || k < 4;
      v.sig_in[k] = kept ? b->sig[k] + q0 : s.zero;
      v.sig_out[k] = kept ? b->sig[k] + q0 : s.sink[k - 4];
    }
    v.rho = b->rho + q0;
    v.lap = b->lap ? b->lap + q0 : s.zero;
    v.isp = b->isp ? b->isp + q0 : s.zero;
    v.g = b->g + q0;
    v.gdp = b->gdp + q0;
    v.state = b->state + q0;
    for (int e = 0; e < 9; e++) {
      v.F[e] = b->F[e] + q0;
      v.Fp[e] = b->Fp[e] + q0;
    }
    for (int k = 0; k < nsub; k++)
      block_step(par, dt, &v, n, &s, 1, 1);
  }
}

const mpm_material_type mpm_material_ngf_hyper = {
  .name = "ngf_hyper",
  .description = "hyperelastic nonlocal granular fluidity, F = Fe Fp with Hencky strain and "
                 "Mandel stress, the NGF local solve and diffusion of g [HS21]",
  .check = ngf_hyper_check,
  .update = ngf_hyper_update,
  .update_point = ngf_hyper_update_point,
  .defgrad = 1,
  .nonlocal = 1,
  .dense = mpm_material_ngf_dense,
};
