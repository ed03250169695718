/* solver_internal.h: what the files of the solver share and nobody else sees
 * (MODEL.md section 2).
 *
 * The step (step.c) names no dimension: it calls the kernels of the run's
 * dimension through a const table (mpm_sim_kernels, kernels.c: one source,
 * kernels.inc, compiled with D = 2 and D = 3), and the unit sums of the
 * per-unit options (units.c), which take the dimension as an argument that
 * is a constant where they are inlined. Here: that table, the small inline
 * pieces of the step every file uses, and the functions of units.c. */
#ifndef MPM_SOLVER_SOLVER_INTERNAL_H
#define MPM_SOLVER_SOLVER_INTERNAL_H

#include <math.h>

#include "solver/solver.h"

/* The points are moved and updated in chunks of this many (step.c,
 * kernels.inc): grid-to-point for the chunk (its velocity gradients and
 * grid velocities kept in an mpm_sim_chunk), then the model's update of the
 * whole chunk at once, then the walls. */
enum { MPM_SIM_CHUNK = 64 };

typedef struct mpm_sim_chunk {
  double L[9][MPM_SIM_CHUNK];                        /* L_p, L[D i + j] */
  double rho[MPM_SIM_CHUNK], lap[MPM_SIM_CHUNK], isp[MPM_SIM_CHUNK];  /* the update's inputs */
  double vg[3][MPM_SIM_CHUNK];                       /* grid velocity that moves p */
  double ag[3][MPM_SIM_CHUNK];                       /* grid acceleration at p */
} mpm_sim_chunk;

/* The kernels of one dimension (kernels.inc). */
typedef struct mpm_sim_kernels {
  int dim;
  /* Step 1 for every point: its weights (located points or the stored
   * stencil; a point outside the mesh is MPM_EOUTSIDE naming it) and the
   * points binned by bands for point-to-grid; every few steps the point
   * store is first reordered by unit row. */
  int (*weights)(mpm_sim *s, mpm_err *err);
  /* Steps 2-3: point-to-grid band by band, then the grid update with the
   * boundary conditions; body force b. */
  void (*grid)(mpm_sim *s, const double b[3]);
  /* Steps 4-5 for points [a, b): grid-to-point (L_p to L[D i + j][p - a],
   * the grid velocity and acceleration at p to ck), x += dt v_grid, the
   * velocity, the volume (not with the B-bar dilatation), CPDI1's extent.
   * With APIC L_p is also the point's affine matrix C_p for the next step. */
  void (*move)(mpm_sim *s, size_t a, size_t b, double *const L[9], mpm_sim_chunk *ck);
  /* Step 7 for points [a, b) moved by the grid velocities ck->vg: the walls,
   * the absorbing layer and the periodic wraps. */
  void (*bookkeeping)(mpm_sim *s, size_t a, size_t b, const mpm_sim_chunk *ck);
} mpm_sim_kernels;

extern const mpm_sim_kernels mpm_sim_kernels_2, mpm_sim_kernels_3;

/* exp(x) for |x| <= 2^-6 (1 beyond): the volume ratio V_{n+1} / V_n =
 * exp(dt tr L) of a step, whose dt tr L is small (2^-6 is a 1.6 % change of
 * volume in one step), as the Taylor series to x^7 in Horner form:
 * truncation below x^8/8! < 1e-19, so within 0.52 ulp of exp as measured
 * against a long-double exp (libm's own: 0.50). No branch and no call, so
 * a loop of it vectorises; the caller takes exp(x) where |x| > 2^-6. */
static inline double mpm_sim_volume_ratio_small(double x)
{
  if (!(fabs(x) <= 0x1p-6))
    return 1.0;
  return 1.0 + x * (1.0 + x * (1.0 / 2 + x * (1.0 / 6 + x * (1.0 / 24 + x * (1.0 / 120
         + x * (1.0 / 720 + x * (1.0 / 5040)))))));
}

/* exp(x): the volume ratio of a step, by the series where it is small. */
static inline double mpm_sim_volume_ratio(double x)
{
  return fabs(x) <= 0x1p-6 ? mpm_sim_volume_ratio_small(x) : exp(x);
}

/* V_p *= exp(dt tr L_p) for the n points of vol, tr L_p = trl[0][k] +
 * trl[1][k] (+ trl[2][k]) over D = nt arrays, the series in a loop that
 * vectorises and libm for the rare large steps. */
static inline void mpm_sim_volume_update(double *restrict vol, const double *const trl[3], int nt,
                                         size_t n, double dt)
{
  const double *restrict t0 = trl[0], *restrict t1 = trl[1], *restrict t2 = trl[2];
  int large = 0;
#pragma omp simd reduction(| : large)
  for (size_t k = 0; k < n; k++) {
    const double x = dt * (nt == 3 ? t0[k] + t1[k] + t2[k] : t0[k] + t1[k]);
    vol[k] *= mpm_sim_volume_ratio_small(x);
    large |= !(fabs(x) <= 0x1p-6);
  }
  if (large)
    for (size_t k = 0; k < n; k++) {
      const double x = dt * (nt == 3 ? t0[k] + t1[k] + t2[k] : t0[k] + t1[k]);
      if (!(fabs(x) <= 0x1p-6))
        vol[k] *= exp(x);
    }
}

/* Step 4's velocity of a point from its velocity v, the grid acceleration
 * ag and velocity vg at it: v_FLIP = v + dt ag, blended with the PIC
 * velocity vg by the FLIP share fl (1: pure FLIP, [DK15]; 0: PIC, which
 * APIC takes). One component. */
static inline double mpm_sim_in_flip(double v, double ag, double vg, double dt, double fl)
{
  const double fv = v + dt * ag;                                /* v_FLIP */
  return fl == 1.0 ? fv : fl * fv + (1.0 - fl) * vg;            /* fl v_FLIP + (1-fl) v_PIC */
}

/* The FLIP share of step 4's velocity blend: time.flip (1: [DK15]); APIC
 * takes the PIC velocity (0). */
static inline double mpm_sim_in_flip_share(const mpm_sim *s)
{
  return s->cfg.time.transfer == MPM_TRANSFER_APIC ? 0.0 : s->cfg.time.flip;
}

/* The absorbing layer of [DK-silo] section 7.1 (absorb.above, .factor):
 * the upward velocity vy of a point at height y at or above the line,
 * scaled by the factor; any other unchanged. */
static inline double mpm_sim_in_absorbed(double above, double factor, double y, double vy)
{
  return y >= above && vy > 0.0 ? vy * factor : vy;
}

/* One component of x_i - x_p, d, on a periodic axis of length len its
 * nearest image. A stencil node lies within 1 + r units of its point (r the
 * stencil's reach beyond the point's unit), so that is its own image while
 * the axis has at least 2 + 2r units, which the input check demands for
 * APIC (a node at exactly half the period away has S = 0). */
static inline double mpm_sim_in_axis_offset(double d, int periodic, double len)
{
  return periodic ? d - len * nearbyint(d / len) : d;
}

/* The mean stress of point p over the run's D axes, (s_xx + s_yy [+ s_zz])
 * / D: in the plane the in-plane mean (the B-bar options' s_m). */
static inline double mpm_sim_in_mean_stress(const mpm_sim *s, size_t p)
{
  const mpm_points *P = s->pts;
  if (s->dim == 3)
    return (P->sxx[p] + P->syy[p] + P->szz[p]) / 3.0;
  return 0.5 * (P->sxx[p] + P->syy[p]);
}

/* "element": the values the unit grid keeps per unit in s->uel, 1 + 2D
 * (the fill, the centroid, the slope of the mean stress; units.c). */
static inline size_t mpm_sim_in_el_width_of(int dim)
{
  return 1 + 2 * (size_t)dim;
}

static inline size_t mpm_sim_in_el_width(const mpm_sim *s)
{
  return mpm_sim_in_el_width_of(s->dim);
}

/* B-bar in point-to-grid: the change of point p's mean stress (its unit
 * uof[p] >= 0) to its unit's mean, or, in a filled unit of "element" (el:
 * s->uel), to 0: the unit acts with its own (mpm_sim_in_element_forces). */
static inline double mpm_sim_in_bbar_shift(const mpm_sim *s, const double *el, size_t p)
{
  const size_t u = (size_t)s->uof[p];
  return el && el[mpm_sim_in_el_width(s) * u] > 0.0
             ? -mpm_sim_in_mean_stress(s, p)
             : s->usum[2 * u + 1] - mpm_sim_in_mean_stress(s, p);
}

/* ---- units.c ------------------------------------------------------------------- */

/* s->xnode for APIC: the coordinates of every stored node, o + i h axis by
 * axis (a periodic axis stores its first node only). */
int mpm_sim_in_node_table(mpm_sim *s, mpm_err *err);

/* With APIC and a convected (CPDI1) extent: every point's stencil within
 * half of each periodic axis (its nodes their own nearest images), else
 * MPM_EINPUT naming the point. */
int mpm_sim_in_apic_extents_fit(const mpm_sim *s, mpm_err *err);

/* The point store in the order of the bands of its unit rows along the
 * mesh's last axis (stable), so that the points of a band lie together in
 * memory. */
int mpm_sim_in_reorder(mpm_sim *s, mpm_err *err);

/* s->uof: the unit of every point at x_{n+1}, once every point moved, for
 * the density of the state decision and the projection of the step's end
 * (s->uof_moved set; mpm_sim_in_unit_stress clears it). */
int mpm_sim_in_units_moved(mpm_sim *s, mpm_err *err);

/* B-bar (mesh.dilatation = "unit" or "element"). Before point-to-grid: the
 * unit of every point (s->uof) and each unit's volume-weighted mean of the
 * mean stress s_m (s->usum), which point-to-grid applies. */
int mpm_sim_in_unit_stress(mpm_sim *s, mpm_err *err);

/* "element", in point-to-grid: f_i += -P_e int_e grad N_i dV over every
 * filled unit e, on the force lanes of the nodal records. */
void mpm_sim_in_element_forces(mpm_sim *s);

/* After grid-to-point (every point's L_p stored, its volume not yet
 * updated): tr L_p replaced by the volume-weighted mean over the point's
 * unit of the step's start, and V_p *= exp(dt tr L_p). */
void mpm_sim_in_unit_dilatation(mpm_sim *s);

/* After the update: the mean stress of every dense point set to the
 * volume-weighted mean over the dense points of its unit of x_{n+1} (the
 * pressure of a mixed Q1/P0 element, one value per unit). */
void mpm_sim_in_unit_project(mpm_sim *s);

#endif
