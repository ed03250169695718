/* hyper.h: the hyperelastic nonlocal granular fluidity point update of
 * [HS21] §3, Algorithm 1 (MODEL.md section 7), and the symmetric 3x3
 * eigen-decomposition, logarithm, exponential and polar decomposition it is
 * built on (hyper.c).
 *
 * The model "ngf_hyper" of mpm_material_table (mpm_material_ngf_hyper): a
 * point carries its total and plastic deformation gradients F and Fp (the
 * table's defgrad = 1: the point store and the batch hold them, the point
 * update takes them as an mpm_mdeform). It reuses the local NGF solve of
 * section 5 (mpm_material_ngf_gstar, mpm_material_ngf_fluidity) and the
 * parameters of mpm_material_params. */
#ifndef MPM_MATERIAL_HYPER_H
#define MPM_MATERIAL_HYPER_H

#include "core/tensor3.h"
#include "material/material.h"

/* Constitutive state of one point of the model. */
typedef struct mpm_material_hyper_point {
  mpm_mat3 F;      /* total deformation gradient, in: F_n, out: F_{n+1} */
  mpm_mat3 Fp;     /* plastic deformation gradient, in: Fp_n, out: Fp_{n+1} */
  mpm_sym3 sigma;  /* Cauchy stress [Pa], in: sigma_n, out: sigma_{n+1} */
  double rho;      /* density rho_{n+1} [kg/m^3] (input) */
  double g;        /* fluidity [1/s], in: g_n, out: g_{n+1} */
  double lap;      /* Laplacian of g at the point [1/(m^2 s)] (input) */
  double isp;      /* p^-1/2 of the g^2 term [Pa^-1/2] (input; 0: the point's own) */
  double gdp;      /* equivalent plastic shear rate [1/s] (output) */
  int state;       /* enum mpm_point_state (output) */
} mpm_material_hyper_point;

/* a = v diag(lam) v^T: eigenvalues lam (unordered) and orthonormal
 * eigenvectors, the columns of v, by cyclic Jacobi rotations. */
void mpm_material_hyper_eigen(mpm_sym3 a, double lam[3], mpm_mat3 *v);

/* ln a of a symmetric positive definite a (NaN entries if it is not). */
mpm_sym3 mpm_material_hyper_log(mpm_sym3 a);

/* exp a of a symmetric a. */
mpm_sym3 mpm_material_hyper_exp(mpm_sym3 a);

/* ln(1 + x) and exp(x) as the update computes them: argument reduction and
 * series without branches or library calls, so that a loop of points vectorises;
 * error below 1 ulp (tests/test_hyper.c measures it). -inf at x = -1, NaN
 * below; exp: +inf above 709.78, 0 below -745.13. */
double mpm_material_hyper_log1p(double x);
double mpm_material_hyper_exp_scalar(double x);

/* Right polar decomposition f = r u of a matrix with det f > 0: r a rotation,
 * u symmetric positive definite. */
void mpm_material_hyper_polar(const mpm_mat3 *f, mpm_mat3 *r, mpm_sym3 *u);

/* Cauchy stress of the elastic state (F, Fp): sigma = J^-1 Re Me Re^T with
 * Me = 2G dev(Ee) + K tr(Ee) I, Ee = ln Ue, Fe = F Fp^-1 = Re Ue, J = det F
 * (NaN if J <= 0). */
mpm_sym3 mpm_material_hyper_stress(const mpm_material_params *par, const mpm_mat3 *F,
                                   const mpm_mat3 *Fp);

/* The elastic state of a given Cauchy stress: F = Fe = Ue symmetric
 * (Fp = I, no rotation) with mpm_material_hyper_stress(F, I) = sigma, for an
 * initial stress; NaN entries when none exists (a tension beyond
 * tr(sigma) / 3K = 1/e). */
mpm_mat3 mpm_material_hyper_F_of_stress(const mpm_material_params *par, mpm_sym3 sigma);

/* One step dt of the NGF point (its F and Fp, sigma, g) with the velocity
 * gradient L (L_ij = d v_i / d x_j) and pt.lap, pt.isp, pt.rho given:
 * MODEL.md section 7, the choices in hyper.c. */
mpm_material_hyper_point mpm_material_hyper_step(const mpm_material_params *par,
                                                 const mpm_mat3 *L, double dt,
                                                 mpm_material_hyper_point pt);

/* The same step purely elastic: F_{n+1} = (I + dt L) F_n,
 * sigma = mpm_material_hyper_stress(F_{n+1}, Fp_n); Fp unchanged, g = gdot_p = 0,
 * no state decision (tension carries stress). */
mpm_material_hyper_point mpm_material_hyper_elastic_step(const mpm_material_params *par,
                                                         const mpm_mat3 *L, double dt,
                                                         mpm_material_hyper_point pt);

#endif
