/* nonlocal.h: the element (unit) fluidity field and its Laplacian for the
 * nonlocal granular fluidity model (MODEL.md section 5 steps 1-2, [DK-silo]
 * §5.2 (i)-(ii), eq. 5.1), on the units of a mesh of either dimension.
 *
 * Per constitutive (sub)step, with point-to-unit membership frozen for the
 * whole MPM step:
 *   1. g_e = sum_p w_pe m_p g_p / sum_p w_pe m_p over the dense points p,
 *      w_pe the share of point p in unit e: 1 for the unit containing its
 *      centre (MPM_NONLOCAL_CENTRE), or the fraction of its extent lying in
 *      e (MPM_NONLOCAL_EXTENT, below); units without dense mass are empty.
 *   2. lap_e = sum_a (g_{a+} - 2 g_e + g_{a-}) / h_a^2 on unit centres (the
 *      5-point stencil in the plane, 7-point on boxes; grid.h), with ghost
 *      values for missing neighbours:
 *        empty unit, free face, frictionless or symmetry wall: g_ghost = g_e
 *          (Neumann, d_n g = 0 at the face);
 *        no-slip wall: g_ghost = -g_e (Dirichlet, g = 0 at the face);
 *        periodic face: the unit on the opposite side (wrap).
 *      Empty units have lap_e = 0.
 * A point then reads the Laplacian of its unit (mpm_nonlocal_point_lap), or
 * under the extent rule the w-weighted mean of lap_e over the filled units it
 * overlaps.
 *
 * Extent rule ([DK-silo] §5.2 (i), material.g_average = "extent"): the
 * extent of point p is the axis-aligned box of half-widths
 * h_a = sum_k |r_ka| about its centre (exact for the extents the fills
 * create, the bounding box of a sheared parallelepiped). It must not be
 * wider than a unit (2 h_a <= dx_a), so it overlaps at most 2^D units; w_pe
 * is the volume of the overlap with unit e over the volume of the part
 * inside the mesh: parts beyond a non-periodic face are dropped and the rest
 * renormalised, periodic faces wrap. An extent inside one unit gives that
 * unit w = 1 exactly, so such a point is treated bitwise as under the
 * centre rule.
 *
 * The g^2 term's p^-1/2 may be sampled per unit (material.p_sample = "unit",
 * docs/model.md): p_e = sum w m p / sum w m over the same dense points; its
 * gradient from the neighbouring filled units (central where both exist,
 * one-sided where one does, 0 where none; walls and empty units do not count,
 * periodic faces wrap), limited so that the linear reconstruction
 * p_e + (x - x_e) . grad p stays >= 0 on the whole unit; isp_e is the exact
 * mean of p^-1/2 of that reconstruction over the unit
 * (mpm_nonlocal_mean_isqrt, mpm_nonlocal_mean_isqrt3). At a free surface p
 * falls linearly to 0 at the top face, and isp_e = 2 / sqrt(p at the bottom
 * face), where the centre value p_e^-1/2 is sqrt(2) times too small; inside
 * a smooth field isp_e = p_e^-1/2 (1 + O(dx^2)).
 *
 * Usage per MPM step (the solver):
 *   mpm_nonlocal_locate(ws, mesh, pts, err);  once, positions x_{n+1}
 *   for each substep:
 *     ws->dense[p] = mpm_material_ngf_dense(par, sigma_p, rho_p);  p_n > 0, rho >= rho_c
 *     mpm_nonlocal_average(ws, n, mass, g, ws->dense);
 *     mpm_nonlocal_laplacian(ws);  (or the implicit diffusion, implicit.h)
 *     mpm_nonlocal_pressure(ws, n, mass, ws->pn, ws->dense);  (unit sampling; pn = p_n)
 *     per point: lap = mpm_nonlocal_point_lap(ws, p), isp = mpm_nonlocal_point_isp(ws, p);
 *       constitutive update
 *
 * The sums run on all threads band by band over bands of units along the
 * mesh's last axis (mesh.h, mpm_mesh_bands, made by the locate): each unit
 * sums its points' shares band by band and in point order within a band
 * (under the centre rule, in point order), so results do not depend on the
 * number of threads. The Laplacian and the unit pressures' p^-1/2 are
 * independent per unit. */
#ifndef MPM_NONLOCAL_NONLOCAL_H
#define MPM_NONLOCAL_NONLOCAL_H

#include <stddef.h>

#include "core/error.h"
#include "core/points.h"
#include "mesh/mesh.h"
#include "nonlocal/grid.h"

/* How a point's g is shared between units. */
enum mpm_nonlocal_rule {
  MPM_NONLOCAL_CENTRE = 0,  /* the whole point goes to the unit containing its centre */
  MPM_NONLOCAL_EXTENT       /* split by the fraction of its extent in each unit
                               ([DK-silo] §5.2 (i)): up to 2^D (unit, weight) pairs
                               per point, see the top of this file */
};

/* Largest number of units one point's extent overlaps (2^D). */
#define MPM_NONLOCAL_PARTS 8

typedef struct mpm_nonlocal {
  mpm_nonlocal_grid grid;  /* the unit grid (grid.h): its dimension and units, 1/h^2,
                              the ghost rules of the faces (grid.ghost[0 .. 2D-1], enum
                              mpm_nonlocal_ghost), an open outlet's faces and a stamp
                              that changes whenever the rules do */
  int rule;             /* enum mpm_nonlocal_rule */
  int nparts;           /* extent rule: pairs per point, 2^D */
  double *sm;           /* [nu] sum m of dense points [kg/m, kg in 3D] */
  double *smg;          /* [nu] sum m g */
  double *ge;           /* [nu] element fluidity g_e [1/s] (0 when empty) */
  double *lap;          /* [nu] lap_e [1/(m^2 s)] (0 when empty) */
  double *pe;           /* [nu] unit pressure p_e [Pa] (0 when empty) */
  double *isp;          /* [nu] unit mean of p^-1/2 [Pa^-1/2] (0 when empty or p_e <= 0) */
  unsigned char *open_mask;  /* [nu] a disc outlet's open unit faces (grid.open_mask), or NULL */
  int *unit;            /* [pcap] frozen unit of each point's centre */
  int *row;             /* [pcap] its unit along the last axis */
  mpm_mesh_bands *bands;  /* the points by bands of those rows, for the unit sums */
  int *part;            /* extent rule: [nparts pcap] units of point p at
                           part[nparts p ...] (unused slots: its centre unit, weight 0) */
  double *w;            /* extent rule: [nparts pcap] their weights (sum 1) */
  unsigned char *dense; /* [pcap] scratch for the caller's dense flags (fill after locate) */
  double *pn;           /* [pcap] scratch for the caller's point pressures p_n [Pa] */
  size_t pcap;          /* capacity of the per-point arrays */
  const struct mpm_nonlocal_diffusion *diffusion;  /* solver of lap_e (field.h); NULL:
                                                      explicit */
  void *diffusion_state;  /* its state (the implicit factorisation), freed with ws */
} mpm_nonlocal;

/* Workspace for mesh m (set up) with room for cap points. face[] holds the
 * enum mpm_bc_kind of its 2 dim faces (MPM_FACE_* order of bc.h: the plane's
 * left, right, bottom, top edges); periodic faces must come in pairs and
 * agree with the mesh's periodic axes. rule is an enum mpm_nonlocal_rule. */
int mpm_nonlocal_alloc(mpm_nonlocal **out, const mpm_mesh *m, const int face[], int rule,
                       size_t cap, mpm_err *err);
void mpm_nonlocal_free(mpm_nonlocal *ws);  /* accepts NULL */

/* Grow the per-point arrays to at least cap points (contents not kept). */
int mpm_nonlocal_reserve(mpm_nonlocal *ws, size_t cap, mpm_err *err);

/* An outlet opens: the units c of face `face` with lo[b] <= c_b < hi[b]
 * along it (the ranges of bc.h's mpm_bc_outlet_faces) become a free
 * surface, Neumann for g, whatever the face's own rule; with open (nu
 * entries, copied) only the units e of that range with open[e] = 1 (a
 * disc's). */
int mpm_nonlocal_open_faces(mpm_nonlocal *ws, int face, const int lo[3], const int hi[3],
                            const unsigned char *open, mpm_err *err);

/* material.g_wall: g on no-slip walls, 0 ([DK-silo] section 4) or zero flux
 * ([D-thesis] App. A.2). */
enum mpm_nonlocal_wall { MPM_NONLOCAL_WALL_DIRICHLET = 0, MPM_NONLOCAL_WALL_NEUMANN };

/* "dirichlet" | "neumann" <-> enum mpm_nonlocal_wall; -1 / NULL if unknown. */
int mpm_nonlocal_wall_from_name(const char *name);
const char *mpm_nonlocal_wall_name(int wall);

/* MPM_NONLOCAL_WALL_NEUMANN: every no-slip face becomes zero flux for g too,
 * instead of g = 0. */
void mpm_nonlocal_walls_neumann(mpm_nonlocal *ws);

/* The mesh nodes where g is held at 0 by the face rules, for a solve on the
 * nodes (steady.h): held[i] = 1 on the faces with the Dirichlet rule, except
 * the nodes of the open units of an outlet; 0 elsewhere. held has m->nnodes
 * entries. */
void mpm_nonlocal_held_nodes(const mpm_nonlocal *ws, const mpm_mesh *m, unsigned char *held);

/* Ghost rule of a face kind (enum mpm_bc_kind); -1 if unknown. */
int mpm_nonlocal_ghost_of_bc(int bc_kind);

/* "centre" | "extent" <-> enum mpm_nonlocal_rule; -1 / NULL if unknown. */
int mpm_nonlocal_rule_from_name(const char *name);
const char *mpm_nonlocal_rule_name(int rule);

/* Freeze the unit of each point of pts (its centre) and, under the extent
 * rule, its (unit, weight) pairs from its extent. Fails with MPM_EOUTSIDE
 * naming the point when it is outside the mesh, with MPM_EINVAL naming it
 * when its extent is wider than a unit. */
int mpm_nonlocal_locate(mpm_nonlocal *ws, const mpm_mesh *m, const mpm_points *pts,
                        mpm_err *err);

/* Element g from the dense points (dense[p] != 0): g_e = sum w m g / sum w m
 * (n the points of the last locate; sums in the order above). */
void mpm_nonlocal_average(mpm_nonlocal *ws, size_t n, const double *mass, const double *g,
                          const unsigned char *dense);

/* lap_e on every non-empty unit from the current g_e (the 5- or 7-point
 * stencil with its ghost rules, grid.h's mpm_nonlocal_grid_laplacian). */
void mpm_nonlocal_laplacian(mpm_nonlocal *ws);

/* Unit pressures p_e = sum w m p / sum w m over the dense points and isp_e, the
 * mean of p^-1/2 over each unit of the limited linear reconstruction (see
 * the top of this file). Call after mpm_nonlocal_average with the same dense
 * flags (it reuses sum m). Sums in point order, as mpm_nonlocal_average. */
void mpm_nonlocal_pressure(mpm_nonlocal *ws, size_t n, const double *mass, const double *p,
                           const unsigned char *dense);

/* Mean of q^-1/2 over s, t in [-1, 1] for q = p0 + a s + c t with
 * p0 > 0 and |a| + |c| <= p0 (exact up to a relative 1e-12: a second-order
 * Taylor expansion when max(|a|, |c|) <= 1e-3 p0, else the closed form
 * with one difference left). */
double mpm_nonlocal_mean_isqrt(double p0, double a, double c);

/* The same over the cube s, t, u in [-1, 1] for q = p0 + a s + b t + c u,
 * |a| + |b| + |c| <= p0 (a relative 1e-10: the Taylor expansion when the
 * largest half-range is <= 1e-3 p0, else the closed form, with two
 * differences left, and its own expansion where the two smaller half-ranges
 * are small against the local p). With c = 0 it is the square's mean. */
double mpm_nonlocal_mean_isqrt3(double p0, double a, double b, double c);

/* Extent rule: sum_e w_pe f_e / sum_e w_pe over the filled units e that
 * point p overlaps; 0 if none is filled. */
double mpm_nonlocal_point_mean(const mpm_nonlocal *ws, const double *f, size_t p);

/* Laplacian seen by point p: its frozen unit's lap_e, or (extent rule) the
 * weighted mean over the filled units it overlaps. */
static inline double mpm_nonlocal_point_lap(const mpm_nonlocal *ws, size_t p)
{
  if (ws->rule == MPM_NONLOCAL_CENTRE)
    return ws->lap[ws->unit[p]];
  return mpm_nonlocal_point_mean(ws, ws->lap, p);
}

/* p^-1/2 for the g^2 term of point p: its frozen unit's isp_e (0: none), or
 * (extent rule) the weighted mean over the filled units it overlaps. */
static inline double mpm_nonlocal_point_isp(const mpm_nonlocal *ws, size_t p)
{
  if (ws->rule == MPM_NONLOCAL_CENTRE)
    return ws->isp[ws->unit[p]];
  return mpm_nonlocal_point_mean(ws, ws->isp, p);
}

#endif
