/* transfer.h: the transfers between points and grid of one step, shared by
 * the files of the solver (not part of solver.h; MODEL.md section 2 steps
 * 1-5 and 7).
 *
 * transfer.c: the weights of every point (step 1: located points, or the
 * stored stencil), the points binned by bands of unit rows, the periodic
 * reordering of the point store, and the grid phase (steps 2-3).
 * Here, inline for the point loops of step.c: the weights of one point,
 * grid-to-point (steps 4-5; the gather point by point, the update of a chunk
 * of points at once) and the walls and wraps of step 7.
 *
 * Nodal values are records of four: after point-to-grid s->nq[i] holds
 * ((mv)_x, (mv)_y, f_x, f_y), after the grid update (v_x, v_y, a_x, a_y), so
 * that a point's share of one node is a few operations on four lanes. */
#ifndef MPM_SOLVER_TRANSFER_H
#define MPM_SOLVER_TRANSFER_H

#include <math.h>

#include "solver/solver.h"

/* The transfer kernels of transfer.inc for the plane (mpm_tr_*2). */
#define DIM 2
#define TR(name) name##2
#define TR_BC mpm_bc
#define TR_BC_APPLY(bc, i, v) mpm_bc_apply_node(bc, i, &(v)[0], &(v)[1])
#include "solver/transfer.inc"
#undef DIM
#undef TR
#undef TR_BC
#undef TR_BC_APPLY

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

/* V_p *= exp(dt tr L_p) for the n points of vol (lxx, lyy: their L), the
 * series in a loop that vectorises and libm for the rare large steps. */
static inline void mpm_sim_volume_update(double *restrict vol, const double *restrict lxx,
                                         const double *restrict lyy, size_t n, double dt)
{
  int large = 0;
#pragma omp simd reduction(| : large)
  for (size_t k = 0; k < n; k++) {
    const double x = dt * (lxx[k] + lyy[k]);
    vol[k] *= mpm_sim_volume_ratio_small(x);
    large |= !(fabs(x) <= 0x1p-6);
  }
  if (large)
    for (size_t k = 0; k < n; k++) {
      const double x = dt * (lxx[k] + lyy[k]);
      if (!(fabs(x) <= 0x1p-6))
        vol[k] *= exp(x);
    }
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
 * (the fill, the centroid, the slope of the mean stress; transfer.c). */
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
 * s->uel), to 0: the unit acts with its own (element_forces). */
static inline double mpm_sim_in_bbar_shift(const mpm_sim *s, const double *el, size_t p)
{
  const size_t u = (size_t)s->uof[p];
  return el && el[mpm_sim_in_el_width(s) * u] > 0.0
             ? -mpm_sim_in_mean_stress(s, p)
             : s->usum[2 * u + 1] - mpm_sim_in_mean_stress(s, p);
}

/* The weights of one point evaluated from its located element. */
typedef struct mpm_sim_in_basis {
  int node[4];
  double S[4], gx[4], gy[4];
} mpm_sim_in_basis;

/* Where the step takes a point's weights from: the stored stencil, or the
 * located point's element basis (bilinear, or any element). The loops of
 * the step are compiled once for each, so the Q4 loops know their four
 * nodes. */
enum { MPM_SIM_IN_STORED = 0, MPM_SIM_IN_Q4, MPM_SIM_IN_ELEMENT };

/* The kind of weights of this run's step. */
static inline int mpm_sim_in_kind(const mpm_sim *s)
{
  if (!s->located)
    return MPM_SIM_IN_STORED;
  return s->mesh.topology == MPM_TOPO_Q4 ? MPM_SIM_IN_Q4 : MPM_SIM_IN_ELEMENT;
}

/* The weights of point p: count, storage node ids, S_ip and gradS_ip, from
 * its located element (into *b) or the stored stencil; kind (a constant in
 * each caller) as mpm_sim_in_kind. */
static inline int mpm_sim_in_weights(const mpm_sim *s, size_t p, int kind, mpm_sim_in_basis *b,
                                     const int **node, const double **S, const double **gx,
                                     const double **gy)
{
  if (kind != MPM_SIM_IN_STORED) {
    *node = b->node;
    *S = b->S;
    *gx = b->gx;
    *gy = b->gy;
  }
  if (kind == MPM_SIM_IN_Q4) {
    mpm_mesh_corners_from(&s->mesh, s->loc_n[p], s->loc_i[p], s->loc_j[p], b->node);
    mpm_mesh_basis_q4(s->loc_u[p], s->loc_v[p], s->mesh.idx, s->mesh.idy, b->S, b->gx, b->gy);
    return 4;
  }
  if (kind == MPM_SIM_IN_ELEMENT)
    return mpm_mesh_basis_at(&s->mesh, s->loc_i[p], s->loc_j[p], s->loc_u[p], s->loc_v[p],
                             b->node, b->S, b->gx, b->gy);
  const mpm_shape_stencil *st = s->st;
  const size_t o = p * (size_t)st->w;
  *node = st->node + o;
  *S = st->S + o;
  *gx = st->dSx + o;
  *gy = st->dSy + o;
  return st->count[p];
}

/* One component of x_i - x_p, d, on a periodic axis of length len its
 * nearest image. */
static inline double mpm_sim_in_axis_offset(double d, int periodic, double len)
{
  return periodic ? d - len * nearbyint(d / len) : d;
}

/* x_i - (x, y) for the node of storage id i (s->xnode), on a periodic axis
 * its image nearest to (x, y). A stencil node lies within 1 + r units of
 * its point (r the stencil's reach beyond the point's unit), so that is its
 * own image while the axis has at least 2 + 2r units, which the input check
 * demands for APIC (a node at exactly half the period away has S = 0). */
static inline void mpm_sim_in_node_offset(const mpm_sim *s, int i, double x, double y,
                                          double *ex, double *ey)
{
  const mpm_mesh *m = &s->mesh;
  const size_t nn = (size_t)m->nnodes;
  *ex = mpm_sim_in_axis_offset(s->xnode[i] - x, m->periodic_x, m->lx);
  *ey = mpm_sim_in_axis_offset(s->xnode[nn + (size_t)i] - y, m->periodic_y, m->ly);
}

/* The same in a 3D run, point x. */
static inline void mpm_sim_in_node_offset3(const mpm_sim *s, int i, const double x[3],
                                           double e[3])
{
  const mpm_mesh3 *m = &s->mesh3;
  const size_t nn = (size_t)m->nnodes;
  e[0] = mpm_sim_in_axis_offset(s->xnode[i] - x[0], m->periodic_x, m->lx);
  e[1] = mpm_sim_in_axis_offset(s->xnode[nn + (size_t)i] - x[1], m->periodic_y, m->ly);
  e[2] = mpm_sim_in_axis_offset(s->xnode[2 * nn + (size_t)i] - x[2], m->periodic_z, m->lz);
}

/* s->xnode for APIC: the coordinates of every stored node, x0 + i dx
 * (likewise y, z; a periodic axis stores its first node only). */
int mpm_sim_in_node_table(mpm_sim *s, mpm_err *err);

/* Step 4 for a point with weights (c, node, S, gx, gy), after the grid
 * update: vg, ag and the in-plane L = {xx, xy, yx, yy} of mpm_tr_gather2. */
static inline void mpm_sim_in_gather(const mpm_sim *s, int c, const int *node,
                                     const double *S, const double *gx, const double *gy,
                                     double vg[2], double ag[2], double L[4])
{
  const double *const g[2] = {gx, gy};
  mpm_tr_gather2((const double (*)[4])s->nq, c, node, S, g, vg, ag, L);
}

/* APIC's C_p from the L of mpm_sim_in_gather: with delta weights the empty
 * nodes of the stencil take the point's velocity (mpm_tr_gather_empty2). */
static inline void mpm_sim_in_affine(const mpm_sim *s, int c, const int *node, const double *S,
                                     const double *gx, const double *gy, const double vg[2],
                                     double L[4])
{
  const double *const g[2] = {gx, gy};
  if (s->mlight > 0.0)                                   /* delta weights */
    mpm_tr_gather_empty2(s->nm, s->mtiny, s->stiny, c, node, S, g, vg, L);
}

/* Step 4's velocity of a point from its velocity v, the grid acceleration
 * ag and velocity vg at it: v_FLIP = v + dt ag, blended with the PIC
 * velocity vg by the FLIP share fl (1: pure FLIP, [DK15]; 0: PIC, which
 * APIC takes). One component; every dimension's step uses it. */
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

/* Step 4 (the rest) and 5 for points [a, b) from what mpm_sim_in_gather gave
 * for point p at index p - a of vgx, vgy, agx, agy, lxx, lyy:
 * v_p += dt sum S a_i (FLIP; blended with the PIC velocity sum S v_i when
 * time.flip < 1; with APIC the PIC velocity), x_p += dt sum S v_i, V_p *= exp(dt tr L_p) (with the
 * B-bar dilatation later, by mpm_sim_in_unit_dilatation); under CPDI1 the
 * extent moves with L_p (before any B-bar change of L_p). */
static inline void mpm_sim_in_advance(mpm_sim *s, size_t a, size_t b, const double *vgx,
                                      const double *vgy, const double *agx, const double *agy,
                                      const double *lxx, const double *lxy, const double *lyx,
                                      const double *lyy)
{
  mpm_points *P = s->pts;
  double *restrict x = P->x, *restrict y = P->y, *restrict vx = P->vx, *restrict vy = P->vy;
  double *restrict vol = P->vol;
  const double dt = s->dt;
  const double fl = mpm_sim_in_flip_share(s);
#pragma omp simd
  for (size_t p = a; p < b; p++) {
    const size_t k = p - a;
    vx[p] = mpm_sim_in_flip(vx[p], agx[k], vgx[k], dt, fl);
    vy[p] = mpm_sim_in_flip(vy[p], agy[k], vgy[k], dt, fl);
    x[p] += dt * vgx[k];
    y[p] += dt * vgy[k];
  }
  if (!s->usum)
    mpm_sim_volume_update(vol + a, lxx, lyy, b - a, dt);     /* V *= exp(dt tr L) */
  if (s->shape->convect)                                     /* CPDI1: r_k <- (I + dt L) r_k */
    for (size_t p = a; p < b; p++) {
      const size_t k = p - a;
      mpm_shape_extent_convect(&P->r1x[p], &P->r1y[p], &P->r2x[p], &P->r2y[p], lxx[k], lxy[k],
                               lyx[k], lyy[k], dt);
    }
}

/* The absorbing layer of [DK-silo] section 7.1 (absorb.above, .factor):
 * the upward velocity vy of a point at height y at or above the line,
 * scaled by the factor; any other unchanged. */
static inline double mpm_sim_in_absorbed(double above, double factor, double y, double vy)
{
  return y >= above && vy > 0.0 ? vy * factor : vy;
}

/* Step 7 for points [a, b), each moved by the grid velocity
 * (vgx, vgy)[p - a]: walls hold, the absorbing layer of [DK-silo] section
 * 7.1 (upward motion high in a silo is elastic waves), periodic wrap. */
static inline void mpm_sim_in_bookkeeping(mpm_sim *s, size_t a, size_t b, const double *vgx,
                                          const double *vgy)
{
  mpm_points *P = s->pts;
  const mpm_mesh m = s->mesh;        /* a copy: its fields stay in registers over the loops */
  double *restrict x = P->x, *restrict y = P->y, *restrict vy = P->vy;
  /* Walls hold. A disconnected point is a free particle: nothing but the
   * wall stops it, so its velocity into the wall is limited to the grid's.
   * A dense one keeps its FLIP velocity, whose wall part the held nodes'
   * a_i already take back (step 3). Only a point outside the mesh can be
   * beyond a wall: one vectorised test first. */
  int out = 0;
#pragma omp simd reduction(| : out)
  for (size_t p = a; p < b; p++)
    out |= mpm_bc_outside(&m, x[p], y[p]);
  for (size_t p = a; out && p < b; p++) {
    if (!mpm_bc_outside(&m, x[p], y[p]))
      continue;
    double vx = P->vx[p], vyp = vy[p];
    mpm_bc_clamp(&s->bc, &m, &x[p], &y[p], &vx, &vyp, vgx[p - a], vgy[p - a]);
    if (P->state[p] != MPM_STATE_DENSE) {
      P->vx[p] = vx;
      vy[p] = vyp;
    }
  }
  const double above = s->cfg.absorb.above, factor = s->cfg.absorb.factor;
  if (above < m.y0 + m.ly) {         /* the absorbing layer lies in the mesh */
#pragma omp simd
    for (size_t p = a; p < b; p++)
      vy[p] = mpm_sim_in_absorbed(above, factor, y[p], vy[p]);
  }
  if (m.periodic_x || m.periodic_y)
    for (size_t p = a; p < b; p++)
      mpm_mesh_wrap(&m, &x[p], &y[p]);
}

/* Step 1 for every point: its weights (located points or the stored
 * stencil; a point outside the mesh is MPM_EOUTSIDE naming it) and the
 * points binned by bands for point-to-grid; every few steps the point store
 * is first reordered by unit row (mpm_sim_in_reorder). */
int mpm_sim_in_weights_all(mpm_sim *s, mpm_err *err);

/* With APIC and a convected (CPDI1) extent: every point's stencil within
 * half of each periodic axis (its nodes their own nearest images), else
 * MPM_EINPUT naming the point (transfer.c). */
int mpm_sim_in_apic_extents_fit(const mpm_sim *s, mpm_err *err);

/* The point store in the order of the bands of its unit rows (stable), so
 * that the points of a band lie together in memory. */
int mpm_sim_in_reorder(mpm_sim *s, mpm_err *err);

/* s->uof: the unit of every point at x_{n+1}, once every point moved, for
 * the density of the state decision and the projection of the step's end
 * (s->uof_moved set; mpm_sim_in_unit_stress clears it). */
int mpm_sim_in_units_moved(mpm_sim *s, mpm_err *err);

/* B-bar (mesh.dilatation = "unit", transfer.c). Before point-to-grid: the
 * unit of every point (s->uof) and each unit's volume-weighted mean of the
 * in-plane mean stress s_m (s->usum), which point-to-grid applies. */
int mpm_sim_in_unit_stress(mpm_sim *s, mpm_err *err);

/* After grid-to-point (every point's L_p stored, its volume not yet
 * updated): tr L_p replaced by the volume-weighted mean over the point's
 * unit of the step's start, and V_p *= exp(dt tr L_p). */
void mpm_sim_in_unit_dilatation(mpm_sim *s);

/* After the update: the in-plane mean stress of every dense point set to
 * the volume-weighted mean over the dense points of its unit of x_{n+1}
 * (the pressure of a mixed Q1/P0 element, one value per unit). In 3D the
 * three of them: the mean stress (s_xx + s_yy + s_zz)/3 and tr L over three
 * axes, the units the boxes (the same functions). */
void mpm_sim_in_unit_project(mpm_sim *s);

/* The end of a step of either dimension, once every point was updated
 * (bad: the largest index of a point whose stress became non-finite, or
 * -1): the report of a blow-up, the B-bar projection, the clock, the speed
 * check and the removal of the points that left (step.c). */
int mpm_sim_in_step_end(mpm_sim *s, long bad, mpm_err *err);

/* unit[p]: the box of a 3D run holding point p now, i + nx (j + ny k), or
 * -1 outside the mesh (transfer.c). */
void mpm_sim_in_boxes(const mpm_sim *s, int *unit);

/* The 3D step's velocity gradients kept over the step, rows of 9 per point
 * (step3.c). */
double *mpm_sim_in_l3(const mpm_sim *s);

/* Steps 2-3: point-to-grid band by band, then the grid update with the
 * boundary conditions; body force (bx, by). */
void mpm_sim_in_grid(mpm_sim *s, double bx, double by);

/* The same for a 3D run (body force b), and its parts for one band of unit
 * layers and one node (transfer3.c). */
void mpm_sim_in_grid3(mpm_sim *s, const double b[3]);
void mpm_sim_in_p2g_band3(const mpm_sim *s, int k, const double b[3]);
void mpm_sim_in_grid_node3(mpm_sim *s, int i, const double b[3], double idt);

/* Step 4 for point p of a 3D run (transfer.inc's gather): the grid velocity
 * vg and acceleration ag at it, and L_p (row-major, L[3 i + j] = dv_i/dx_j). */
void mpm_sim_in_gather3(const mpm_sim *s, size_t p, double vg[3], double ag[3], double L[9]);

/* APIC in 3D: the L of mpm_sim_in_gather3 becomes point p's C_p (with delta
 * weights its empty nodes taking the point's velocity vg, as
 * mpm_sim_in_affine in the plane) and is stored. */
void mpm_sim_in_affine3(mpm_sim *s, size_t p, const double vg[3], double L[9]);

#endif
