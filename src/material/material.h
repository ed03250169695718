/* material.h: constitutive models behind one interface (MODEL.md sections 4-5).
 *
 * A model is a const mpm_material_type in mpm_material_table (NULL ended),
 * chosen by its name in the input. Its parameters live in mpm_material_params
 * (filled from the input, derived constants by mpm_material_params_derive);
 * nothing is global. The update advances the stress of one point over dt with
 * the velocity gradient L fixed, given the new density pt->rho. */
#ifndef MPM_MATERIAL_MATERIAL_H
#define MPM_MATERIAL_MATERIAL_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "core/config.h"
#include "core/error.h"
#include "core/tensor3.h"

typedef struct mpm_material_params {
  /* from the input */
  double E, nu;          /* Young's modulus [Pa], Poisson ratio */
  double rho_s, rho_c;   /* grain density, critical (disconnection) density [kg/m^3] */
  double mu_s, mu_2, I0; /* mu(I): static and limit friction, I0 */
  double d;              /* grain diameter [m] */
  double A, t0;          /* NGF amplitude and time scale [s] */
  int form;              /* NGF PDE form, enum mpm_material_ngf_form (0: [DK-silo]) */
  int p_sample;          /* NGF: p^-1/2 of the g^2 term, enum mpm_material_ngf_p_sample */
  double t_seed;         /* NGF seeding time [s]: the local mu_i update runs for
                            t < t_seed, then g = gdot_p / mu (mpm_material_ngf_seed); 0: none */
  /* derived (mpm_material_params_derive) */
  double G, K;           /* shear and bulk modulus [Pa] */
  double dmu;            /* mu_2 - mu_s */
  double b;              /* dmu / I0 */
  double xi;             /* I0 / (d sqrt(rho_s)) [sqrt(m/kg)] */
} mpm_material_params;

/* Fill G, K, dmu, b, xi from the input values. */
void mpm_material_params_derive(mpm_material_params *par);

/* [DK15] Table 1 (glass beads, d = 5 mm): the input defaults, the
 * constitutive driver's built-in material and the tests' material. */
#define MPM_DK15_NU 0.3
#define MPM_DK15_RHO_S 2450.0
#define MPM_DK15_RHO_C 1500.0
#define MPM_DK15_MU_S 0.3819
#define MPM_DK15_MU_2 0.6435
#define MPM_DK15_I0 0.279
#define MPM_DK15_D 0.005

/* Set nu, rho_s, rho_c, mu_s, mu_2, I0 and d of cfg->material to Table 1. */
void mpm_material_config_dk15(mpm_config *cfg);

/* The parameters of a resolved input's material section, derived constants
 * filled (the model itself is looked up by name: mpm_material_lookup). */
void mpm_material_params_from_config(mpm_material_params *par, const mpm_config *cfg);

/* Constitutive state of one point, gathered from the point store. */
typedef struct mpm_mpoint {
  mpm_sym3 sigma;  /* Cauchy stress [Pa], in: sigma_n, out: sigma_{n+1} */
  double rho;      /* density rho_{n+1} [kg/m^3] (input) */
  double g;        /* fluidity [1/s], in: g_n, out: g_{n+1} */
  double lap;      /* Laplacian of g of the point's unit [1/(m^2 s)] (input; read
                      only by nonlocal models, mpm_nonlocal_point_lap) */
  double isp;      /* p^-1/2 for the g^2 term of a nonlocal model [Pa^-1/2] (input;
                      mpm_nonlocal_point_isp); 0: the point's own p_tr^-1/2 */
  double gdp;      /* equivalent plastic shear rate [1/s] (output) */
  int state;       /* enum mpm_point_state (output) */
} mpm_mpoint;

/* The deformation gradients of a point of a model that carries them
 * (mpm_material_type.defgrad): in at t_n, out at t_{n+1}. */
typedef struct mpm_mdeform {
  mpm_mat3 F;      /* total deformation gradient */
  mpm_mat3 Fp;     /* plastic deformation gradient */
} mpm_mdeform;

/* One constitutive update: sigma_n -> sigma_{n+1} of pt over dt with L fixed;
 * def: the point's deformation gradients for a model that carries them,
 * else not read (may be NULL). */
typedef void (*mpm_material_update_fn)(const mpm_material_params *par, const mpm_mat3 *L, double dt,
                                       mpm_mpoint *pt, mpm_mdeform *def);

/* n points of a run of dimension dim, as structure-of-arrays views: entry
 * k of each array is point k. In the plane (dim 2) the out-of-plane velocity
 * gradients and shear stresses are zero: L has the D x D in-plane entries
 * and only xx, yy, zz, xy of the stress are read and written. */
typedef struct mpm_material_batch {
  size_t n;
  int dim;                               /* 2 (plane strain) or 3 */
  const double *L[9];                    /* L[D i + j] = dv_i/dx_j, i, j < D [1/s] */
  const double *rho;                     /* rho_{n+1} [kg/m^3] */
  const double *lap, *isp;               /* nonlocal inputs (mpm_mpoint); NULL: 0 */
  double *sig[6];                        /* stress in the order of mpm_sym3 (xx yy zz xy
                                            yz zx; 4 in the plane), in: sigma_n, out:
                                            sigma_{n+1} [Pa] */
  double *g, *gdp;                       /* fluidity and gdot_p, as in mpm_mpoint */
  int *state;
  double *F[9], *Fp[9];                  /* F_ij, Fp_ij at [3 i + j] (a model with
                                            defgrad only; NULL otherwise) */
} mpm_material_batch;

/* Powers of two that scale the terms of a model's quadratic exactly, so that
 * its squares and products cannot under- or overflow as p -> 0+:
 * *down = 2^-e and *up = 2^e for e the exponent of m (m = f 2^e with f in
 * [1/2, 1), as frexp gives it), clamped to [-1021, 1022] so both are normal
 * numbers; e = 0 when m is zero, subnormal or not finite. Multiplying by them
 * rounds nothing unless the product under- or overflows, and where nothing
 * does, a scaling changes no rounding of the root. Integer operations on the
 * bits of m only (no library call), so a loop of updates vectorises. */
static inline void mpm_material_pow2(double m, double *down, double *up)
{
  uint64_t b;
  memcpy(&b, &m, sizeof b);
  const int64_t x = (int64_t)(b >> 52 & 0x7ff);                 /* biased exponent of m */
  int64_t e = x - 1022;
  e = x == 0 || x == 0x7ff ? 0 : e < -1021 ? -1021 : e > 1022 ? 1022 : e;
  const uint64_t d = (uint64_t)(1023 - e) << 52, u = (uint64_t)(1023 + e) << 52;
  memcpy(down, &d, sizeof d);                                    /* 2^-e */
  memcpy(up, &u, sizeof u);                                      /* 2^e */
}

/* A model's kernel (mpm_material_kernel_fn) written to be inlined into
 * mpm_material_loop (its update) whatever its size. */
#if defined(__GNUC__)
#define MPM_MATERIAL_KERNEL static inline __attribute__((always_inline))
#else
#define MPM_MATERIAL_KERNEL static inline
#endif

/* A model's update of one point by value (the point in, the point out):
 * the form a model writes its update in, so that a batch keeps each point in
 * registers and updates several points at once. */
typedef mpm_mpoint (*mpm_material_kernel_fn)(const mpm_material_params *par, mpm_mat3 L,
                                             double dt, mpm_mpoint pt);

/* One pass of the kernel k over the points of b in D dimensions (D a
 * constant where this is inlined; nonlocal: lap and isp read). The arrays
 * are restrict locals and the point a value (no address taken), so the
 * compiler keeps it in registers and updates several points at once; the
 * plane's absent entries are the constant 0, so the plane pass is the
 * plane-strain update as written. */
MPM_MATERIAL_KERNEL void mpm_material_pass(const mpm_material_params *par, double dt,
                                           const mpm_material_batch *b,
                                           mpm_material_kernel_fn k, int D, int nonlocal)
{
  const size_t n = b->n;
  const double *restrict l00 = b->L[0], *restrict l01 = b->L[1];
  const double *restrict l10 = b->L[D], *restrict l11 = b->L[D + 1];
  const double *restrict l02 = b->L[2], *restrict l12 = b->L[5];
  const double *restrict l20 = b->L[6], *restrict l21 = b->L[7], *restrict l22 = b->L[8];
  const double *restrict rho = b->rho, *restrict lap = b->lap, *restrict isp = b->isp;
  double *restrict sxx = b->sig[0], *restrict syy = b->sig[1], *restrict szz = b->sig[2];
  double *restrict sxy = b->sig[3], *restrict syz = b->sig[4], *restrict szx = b->sig[5];
  double *restrict g = b->g, *restrict gdp = b->gdp;
  int *restrict state = b->state;
  const mpm_material_params pl = *par;   /* a local copy: its fields load unconditionally */
#pragma omp simd
  for (size_t q = 0; q < n; q++) {
    const mpm_mat3 L = D == 3 ? (mpm_mat3){{{l00[q], l01[q], l02[q]}, {l10[q], l11[q], l12[q]},
                                            {l20[q], l21[q], l22[q]}}}
                              : (mpm_mat3){{{l00[q], l01[q], 0.0}, {l10[q], l11[q], 0.0},
                                            {0.0, 0.0, 0.0}}};
    mpm_mpoint pt = {
      .sigma = {sxx[q], syy[q], szz[q], sxy[q], D == 3 ? syz[q] : 0.0, D == 3 ? szx[q] : 0.0},
      .rho = rho[q],
      .g = g[q], .lap = nonlocal ? lap[q] : 0.0, .isp = nonlocal ? isp[q] : 0.0,
      .gdp = gdp[q], .state = state[q],
    };
    pt = k(&pl, L, dt, pt);
    sxx[q] = pt.sigma.xx;
    syy[q] = pt.sigma.yy;
    szz[q] = pt.sigma.zz;
    sxy[q] = pt.sigma.xy;
    if (D == 3) {
      syz[q] = pt.sigma.yz;
      szx[q] = pt.sigma.zx;
    }
    g[q] = pt.g;
    gdp[q] = pt.gdp;
    state[q] = pt.state;
  }
}

/* nsub updates of dt each, L fixed, of every point of b by the kernel k:
 * each point is gathered into an mpm_mpoint and scattered back, so the
 * result is exactly that of the update point by point (the points are
 * independent, so their substeps run as passes over all of them). A model's
 * update calls it with its own kernel, which is inlined into the loop once
 * per dimension (the kernels are written without library calls and branch
 * on values only, so the loop vectorises). */
MPM_MATERIAL_KERNEL void mpm_material_loop(const mpm_material_params *par, double dt,
                                           int nsub, const mpm_material_batch *b,
                                           mpm_material_kernel_fn k)
{
  const int nl = b->lap && b->isp;
  for (int s = 0; s < nsub; s++) {
    if (b->dim == 3 && nl)
      mpm_material_pass(par, dt, b, k, 3, 1);
    else if (b->dim == 3)
      mpm_material_pass(par, dt, b, k, 3, 0);
    else if (nl)
      mpm_material_pass(par, dt, b, k, 2, 1);
    else
      mpm_material_pass(par, dt, b, k, 2, 0);
  }
}

typedef struct mpm_material_type {
  const char *name;
  const char *description;
  /* Check the parameters this model uses (ranges); message names the key. */
  int (*check)(const mpm_material_params *par, mpm_err *err);
  /* The update of a batch of points (nsub times each, L fixed), the one the
   * step calls: mpm_material_loop with the model's own kernel inlined.
   * sigma_n -> sigma_{n+1} over dt; never fails: physical limits (p -> 0,
   * disconnection) are states, not errors. */
  void (*update)(const mpm_material_params *par, double dt, int nsub,
                 const mpm_material_batch *b);
  /* The same kernel for one point (the constitutive driver, the tests). */
  mpm_material_update_fn update_point;
  /* 1 for a model whose points carry their deformation gradients F and Fp
   * (mpm_mdeform; the batch's F and Fp, the point store's MPM_POINT_DEFGRAD
   * fields, filled with F = Fe of the initial stress, Fp = I): the
   * hyperelastic NGF. */
  int defgrad;
  /* 1 for nonlocal models: before each (sub)step the caller fills pt->lap from
   * the element fluidity of the points the model calls dense (nonlocal.h,
   * mpm_nonlocal_field); local models ignore pt->lap. */
  int nonlocal;
  /* Nonlocal models: 1 if a point with stress sigma_n and density rho_{n+1}
   * contributes to the element field this step. */
  int (*dense)(const mpm_material_params *par, mpm_sym3 sigma_n, double rho);
  /* Seeding ([DK-silo] section 6: g = 0 is always a solution). While
   * t < par->t_seed a nonlocal model runs locally: the model before_seed,
   * after which the field of every dense point is set once by
   * seed(sigma, gdot_p); or, without one, its own update with lap = 0. */
  const struct mpm_material_type *before_seed;
  double (*seed)(mpm_sym3 sigma, double gdp);
  /* Nonlocal models with a steady form (material.diffusion = "steady",
   * nonlocal/steady.h, MODEL.md section 6), NULL otherwise:
   * steady_terms: the coefficient c = |F(mu)| = (A d / xi)^2 and the local
   *   fluidity g_loc [1/s] of A^2 d^2 lap(g) = c (g - g_loc) at stress sigma
   *   (the start of the step), both 0 where p <= 0;
   * update_steady: the update of a batch with g the fluidity the steady solve
   *   gives each point for the step (input; g_{n+1} = g when it is dense), and
   *   update_steady_point the same for one point. */
  void (*steady_terms)(const mpm_material_params *par, mpm_sym3 sigma, double *c, double *gloc);
  void (*update_steady)(const mpm_material_params *par, double dt, int nsub,
                        const mpm_material_batch *b);   /* as update */
  mpm_material_update_fn update_steady_point;
} mpm_material_type;

/* gdot_p of a stress-free point in every model: its whole deviatoric rate
 * is inelastic, sqrt(2 D0:D0) (the p -> 0+ limit of the dense update, so
 * gdot_p is continuous across disconnection and reconnection). */
static inline double mpm_material_free_gdp(mpm_sym3 D)
{
  const mpm_sym3 D0 = mpm_sym3_dev(D);
  return sqrt(2.0 * mpm_sym3_ddot(D0, D0));
}

/* Jaumann trial stress of every hypoelastic model (MODEL.md section 4 step 2):
 * sigma_tr = sigma_n + dt (C:D + W sigma_n - sigma_n W), D = sym L, W = skw L. */
static inline mpm_sym3 mpm_material_trial(const mpm_material_params *par, mpm_sym3 D,
                                          const mpm_mat3 *L, mpm_sym3 sigma, double dt)
{
  mpm_mat3 W = mpm_mat3_skw(L);
  mpm_sym3 rate = mpm_sym3_add(mpm_sym3_elastic(D, par->G, par->K),  /* C:D */
                               mpm_sym3_spin(&W, sigma));           /* W s - s W */
  return mpm_sym3_axpy(sigma, dt, rate);
}

extern const mpm_material_type mpm_material_elastic;  /* Jaumann hypoelastic */
extern const mpm_material_type mpm_material_mu_i;     /* trans-phase mu(I) [DK15] */
extern const mpm_material_type mpm_material_ngf;      /* trans-phase NGF [DK-silo] */
extern const mpm_material_type mpm_material_ngf_hyper;  /* hyperelastic NGF [HS21] */
extern const mpm_material_type *const mpm_material_table[];

/* Shared parameter checks for models (message names the key and range). */
int mpm_material_check_elastic(const mpm_material_params *par, mpm_err *err);

/* Model by name, NULL if unknown. */
const mpm_material_type *mpm_material_lookup(const char *name);

/* P-wave speed sqrt((K + 4G/3) / rho) for the time-step limit. */
double mpm_material_wave_speed(const mpm_material_params *par, double rho);

/* ---- mu(I) (mu_i.c) */

/* gdot_p of the mu(I) law at stress sigma (state: enum mpm_point_state):
 * 0 if mu <= mu_s, else xi sqrt(p) (mu - mu_s) / (mu_2 - mu) (+inf if
 * mu >= mu_2); sqrt(2 D0:D0) if state is disconnected. */
double mpm_material_mu_i_gdp(const mpm_material_params *par, mpm_sym3 sigma, mpm_sym3 D,
                             int state);

/* ---- nonlocal granular fluidity (ngf.c, MODEL.md section 5) ----------------
 * The PDE's local part, selectable:
 *   MPM_NGF_DK:   - Delta_mu (mu_s - mu)/(mu_2 - mu) g   [DK-silo] eq. 2.1 (A = 0: mu(I))
 *   MPM_NGF_HS21: - (mu_s - mu) g                       [HS21] eq. 6 (A = 0: mu_s + b I)
 * both with - b sqrt(rho_s d^2 / p) mu g^2 and the diffusion A^2 d^2 lap(g). */
enum mpm_material_ngf_form { MPM_NGF_DK = 0, MPM_NGF_HS21 };

/* "dk" | "hs21" <-> enum mpm_material_ngf_form; -1 / NULL if unknown. */
int mpm_material_ngf_form_from_name(const char *name);
const char *mpm_material_ngf_form_name(int form);

/* Where the g^2 term b sqrt(rho_s d^2 / p) mu g^2 samples p^-1/2:
 *   MPM_NGF_P_POINT: the point's own p_tr^-1/2, as [DK-silo] §5.2 (with A = 0
 *                    the update is exactly mu(I) point by point);
 *   MPM_NGF_P_UNIT:  the mean of p^-1/2 over the point's unit, p reconstructed
 *                    linearly from the unit pressures (nonlocal.h,
 *                    mpm_nonlocal_pressure); it integrates the p^-1/2 of a
 *                    free surface, where the point value under-weights the
 *                    top unit by a factor up to sqrt(2) when g is smooth on the
 *                    unit scale (A d >~ dx; docs/model.md). */
enum mpm_material_ngf_p_sample { MPM_NGF_P_POINT = 0, MPM_NGF_P_UNIT };

/* "point" | "unit" <-> enum mpm_material_ngf_p_sample; -1 / NULL if unknown. */
int mpm_material_ngf_p_sample_from_name(const char *name);
const char *mpm_material_ngf_p_sample_name(int sample);

/* 1 if the point is dense this step (contributes to the element g):
 * p_n = -tr(sigma_n)/3 > 0 and rho_{n+1} >= rho_c. */
int mpm_material_ngf_dense(const mpm_material_params *par, mpm_sym3 sigma_n, double rho);

/* g_{n+1} of MODEL.md section 5 step 4: the root of the quadratic in x = g_{n+1}
 * with the physical choice, for time step dt, pressure p = p_tr > 0, trial
 * shear stress tau_tr >= 0, diffused fluidity gstar = g* >= 0,
 * mug_n = mu_n g_n (start of step) and isp, the p^-1/2 of the g^2 term
 * (0: 1/sqrt(p)). Returns x >= 0. */
double mpm_material_ngf_fluidity(const mpm_material_params *par, double dt, double p, double tau_tr,
                                 double gstar, double mug_n, double isp);

/* tau / tau_tr = p / (p + G dt g) of the return of a dense point of
 * fluidity g (MODEL.md section 5, eq. 5.5: tau = tau_tr - G dt gdot_p with
 * gdot_p = g mu); 1 when dt = 0. */
static inline double mpm_material_ngf_return_ratio(const mpm_material_params *par, double dt,
                                                   double p, double g)
{
  return dt > 0.0 ? p / (par->G * dt * g + p) : 1.0;
}

/* g* = max(0, g_n + (dt/t0) A^2 d^2 lap): the explicitly diffused fluidity of
 * MODEL.md section 5 step 3, the g* of mpm_material_ngf_fluidity. */
double mpm_material_ngf_gstar(const mpm_material_params *par, double dt, double g_n, double lap);

/* Seeding from a local run: g = gdot_p / mu, mu = tau / p (0 if p <= 0 or tau = 0). */
double mpm_material_ngf_seed(mpm_sym3 sigma, double gdp);

/* c = (dt/t0) A^2 d^2 [m^2]: a step dt diffuses g by c lap(g) (MODEL.md section 5). */
double mpm_material_ngf_diffusivity(const mpm_material_params *par, double dt);

/* Explicit-diffusion number (dt/n_sub) A^2 d^2 / t0 (2/dx^2 + 2/dy^2
 * [+ 2/dz^2 in 3D: dz > 0; a plane run passes dz = 0]); the update is
 * stable when it is <= 1. */
double mpm_material_ngf_diffusion_number(const mpm_material_params *par, double dt, int n_sub,
                                         double dx, double dy, double dz);

/* MPM_OK if the diffusion number is <= 1, else MPM_EINPUT with the smallest
 * n_sub that satisfies it. */
int mpm_material_ngf_check_diffusion(const mpm_material_params *par, double dt, int n_sub,
                                     double dx, double dy, double dz, mpm_err *err);

#endif
