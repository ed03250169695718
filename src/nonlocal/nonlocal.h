/* nonlocal.h: the element (unit) fluidity field and its Laplacian for the
 * nonlocal granular fluidity model (MODEL.md section 5 steps 1-2, [DK-silo]
 * §5.2 (i)-(ii), eq. 5.1).
 *
 * Per constitutive (sub)step, with point-to-unit membership frozen for the
 * whole MPM step:
 *   1. g_e = sum_p w_pe m_p g_p / sum_p w_pe m_p over the dense points p,
 *      w_pe the share of point p in unit e: 1 for the unit containing its
 *      centre (MPM_NONLOCAL_CENTRE), or the fraction of its extent lying in
 *      e (MPM_NONLOCAL_EXTENT, below); units without dense mass are empty.
 *   2. lap_e = (g_E - 2 g_e + g_W)/dx^2 + (g_N - 2 g_e + g_S)/dy^2 on unit
 *      centres, with ghost values for missing neighbours:
 *        empty unit, free edge, frictionless or symmetry wall: g_ghost = g_e
 *          (Neumann, d_n g = 0 at the face);
 *        no-slip wall: g_ghost = -g_e (Dirichlet, g = 0 at the face);
 *        periodic edge: the unit on the opposite side (wrap).
 *      Empty units have lap_e = 0.
 * A point then reads the Laplacian of its unit (mpm_nonlocal_point_lap), or
 * under the extent rule the w-weighted mean of lap_e over the filled units it
 * overlaps.
 *
 * Extent rule ([DK-silo] §5.2 (i), material.g_average = "extent"): the
 * extent of point p is the axis-aligned rectangle of half-widths
 * hx = |r1x| + |r2x|, hy = |r1y| + |r2y| about its centre (exact for the
 * rectangular extents the fills create, the bounding box of a sheared
 * parallelogram). It must not be wider than a unit (2 hx <= dx, 2 hy <= dy),
 * so it overlaps at most 2 x 2 units; w_pe is the area of the overlap with
 * unit e over the area of the part inside the mesh: parts beyond a
 * non-periodic edge are dropped and the rest renormalised, periodic edges
 * wrap. An extent inside one unit gives that unit w = 1 exactly, so such a
 * point is treated bitwise as under the centre rule.
 *
 * The g^2 term's p^-1/2 may be sampled per unit (material.p_sample = "unit",
 * docs/model.md): p_e = sum w m p / sum w m over the same dense points; its
 * gradient from the neighbouring filled units (central where both exist,
 * one-sided where one does, 0 where none; walls and empty units do not count,
 * periodic edges wrap), limited so that the linear reconstruction
 * p_e + (x - x_e) . grad p stays >= 0 on the whole unit; isp_e is the exact
 * mean of p^-1/2 of that reconstruction over the unit
 * (mpm_nonlocal_mean_isqrt). At a free surface p falls linearly to 0 at the
 * top face, and isp_e = 2 / sqrt(p at the bottom face), where the centre
 * value p_e^-1/2 is sqrt(2) times too small; inside a smooth field
 * isp_e = p_e^-1/2 (1 + O(dx^2)).
 *
 * Usage per MPM step (the solver):
 *   mpm_nonlocal_locate_extents(ws, mesh, n, x, y, r, err);  once, positions x_{n+1}
 *   for each substep:
 *     ws->dense[p] = mpm_material_ngf_dense(par, sigma_p, rho_p);  p_n > 0, rho >= rho_c
 *     mpm_nonlocal_average(ws, n, mass, g, ws->dense);
 *     mpm_nonlocal_laplacian(ws);  (or the implicit diffusion, implicit.h)
 *     mpm_nonlocal_pressure(ws, n, mass, ws->pn, ws->dense);  (unit sampling; pn = p_n)
 *     per point: lap = mpm_nonlocal_point_lap(ws, p), isp = mpm_nonlocal_point_isp(ws, p);
 *       constitutive update
 *
 * The sums run on all threads band by band over bands of unit rows
 * (mesh.h, mpm_mesh_bands, made by the locate): each unit sums its points'
 * shares band by band and in point order within a band (under the centre
 * rule, in point order), so results do not depend on the number of threads.
 * The Laplacian and the unit pressures' p^-1/2 are independent per unit. */
#ifndef MPM_NONLOCAL_NONLOCAL_H
#define MPM_NONLOCAL_NONLOCAL_H

#include <stddef.h>

#include "core/error.h"
#include "mesh/mesh.h"
#include "nonlocal/grid.h"

/* How a point's g is shared between units. */
enum mpm_nonlocal_rule {
  MPM_NONLOCAL_CENTRE = 0,  /* the whole point goes to the unit containing its centre */
  MPM_NONLOCAL_EXTENT       /* split by the fraction of its extent in each unit
                               ([DK-silo] §5.2 (i)): up to four (unit, weight) pairs
                               per point, see the top of this file */
};

/* Largest number of units one point's extent overlaps. */
#define MPM_NONLOCAL_PARTS 4

typedef struct mpm_nonlocal {
  int nx, ny;           /* units */
  mpm_nonlocal_grid grid;  /* the unit grid (grid.h): 1/dx^2, 1/dy^2, the ghost rules of
                              the left, right, bottom and top edges (grid.ghost[0..3],
                              enum mpm_nonlocal_ghost), an open outlet's faces and a
                              stamp that changes whenever the rules do */
  int rule;             /* enum mpm_nonlocal_rule */
  double *sm;           /* [nx*ny] sum m of dense points [kg/m] */
  double *smg;          /* [nx*ny] sum m g [kg/(m s)] */
  double *ge;           /* [nx*ny] element fluidity g_e [1/s] (0 when empty) */
  double *lap;          /* [nx*ny] lap_e [1/(m^2 s)] (0 when empty) */
  double *pe;           /* [nx*ny] unit pressure p_e [Pa] (0 when empty) */
  double *isp;          /* [nx*ny] unit mean of p^-1/2 [Pa^-1/2] (0 when empty or p_e <= 0) */
  int *unit;            /* [pcap] frozen unit of each point's centre, i + nx j */
  int *row;             /* [pcap] its row j */
  mpm_mesh_bands *bands;  /* the points by bands of those rows, for the unit sums */
  int *part;            /* extent rule: [MPM_NONLOCAL_PARTS pcap] units of point p at
                           part[4p .. 4p+3] (unused slots: its centre unit, weight 0) */
  double *w;            /* extent rule: [MPM_NONLOCAL_PARTS pcap] their weights (sum 1) */
  unsigned char *dense; /* [pcap] scratch for the caller's dense flags (fill after locate) */
  double *pn;           /* [pcap] scratch for the caller's point pressures p_n [Pa] */
  size_t pcap;          /* capacity of the per-point arrays */
  const struct mpm_nonlocal_diffusion *diffusion;  /* solver of lap_e (field.h); NULL:
                                                      explicit */
  void *diffusion_state;  /* its state (the implicit factorisation), freed with ws */
} mpm_nonlocal;

/* Workspace for mesh m (set up) with room for cap points. edge[4] holds the
 * enum mpm_bc_kind of the left, right, bottom and top edges; periodic edges
 * must come in pairs and agree with m->periodic_x / periodic_y. rule is an
 * enum mpm_nonlocal_rule. */
int mpm_nonlocal_alloc(mpm_nonlocal **out, const mpm_mesh *m, const int edge[4], int rule,
                       size_t cap, mpm_err *err);
void mpm_nonlocal_free(mpm_nonlocal *ws);  /* accepts NULL */

/* Grow the per-point arrays to at least cap points (contents not kept). */
int mpm_nonlocal_reserve(mpm_nonlocal *ws, size_t cap, mpm_err *err);

/* An outlet opens: the faces lo .. hi-1 of edge `edge` (left, right,
 * bottom, top; along it, unit columns on the bottom and top, rows on the
 * left and right) become a free surface, Neumann for g, whatever the
 * edge's own rule. */
void mpm_nonlocal_open_faces(mpm_nonlocal *ws, int edge, int lo, int hi);

/* material.g_wall: g on no-slip walls, 0 ([DK-silo] section 4) or zero flux
 * ([D-thesis] App. A.2). */
enum mpm_nonlocal_wall { MPM_NONLOCAL_WALL_DIRICHLET = 0, MPM_NONLOCAL_WALL_NEUMANN };

/* "dirichlet" | "neumann" <-> enum mpm_nonlocal_wall; -1 / NULL if unknown. */
int mpm_nonlocal_wall_from_name(const char *name);
const char *mpm_nonlocal_wall_name(int wall);

/* MPM_NONLOCAL_WALL_NEUMANN: every no-slip edge becomes zero flux for g too,
 * instead of g = 0. */
void mpm_nonlocal_walls_neumann(mpm_nonlocal *ws);

/* The mesh nodes where g is held at 0 by the edge rules, for a solve on the
 * nodes (steady.h): held[i] = 1 on the edges with the Dirichlet rule, except
 * the nodes of an open outlet; 0 elsewhere. held has m->nnodes entries. */
void mpm_nonlocal_held_nodes(const mpm_nonlocal *ws, const mpm_mesh *m, unsigned char *held);

/* Ghost rule of an edge kind (enum mpm_bc_kind); -1 if unknown. */
int mpm_nonlocal_ghost_of_bc(int bc_kind);

/* "centre" | "extent" <-> enum mpm_nonlocal_rule; -1 / NULL if unknown. */
int mpm_nonlocal_rule_from_name(const char *name);
const char *mpm_nonlocal_rule_name(int rule);

/* Freeze the unit of each of the n points at (x, y) (its centre) and, under
 * the extent rule, its (unit, weight) pairs from the extent half-vectors
 * r = {r1x, r1y, r2x, r2y} (arrays of n each; not read under the centre
 * rule, where r may be NULL). Fails with MPM_EOUTSIDE naming the point index
 * when a point is outside the mesh, with MPM_EINVAL naming it when its
 * extent is wider than a unit or r is NULL under the extent rule. */
int mpm_nonlocal_locate_extents(mpm_nonlocal *ws, const mpm_mesh *m, size_t n, const double *x,
                                const double *y, const double *const r[4], mpm_err *err);

/* The same without extents (r = NULL): the centre rule only. */
int mpm_nonlocal_locate(mpm_nonlocal *ws, const mpm_mesh *m, size_t n, const double *x,
                        const double *y, mpm_err *err);

/* Element g from the dense points (dense[p] != 0): g_e = sum w m g / sum w m
 * (n the points of the last locate; sums in the order above). */
void mpm_nonlocal_average(mpm_nonlocal *ws, size_t n, const double *mass, const double *g,
                          const unsigned char *dense);

/* lap_e on every non-empty unit from the current g_e (5-point, ghost rules;
 * the stencil of grid.h, mpm_nonlocal_grid_laplacian). */
void mpm_nonlocal_laplacian(mpm_nonlocal *ws);

/* The four sides of a unit, in the order of the mesh edges they face (the
 * faces 0 .. 3 of grid.h). */
enum mpm_nonlocal_side { MPM_SIDE_W = 0, MPM_SIDE_E, MPM_SIDE_S, MPM_SIDE_N };

/* The ghost rules of the 5-point Laplacian (mpm_nonlocal_grid_side, the one
 * rule of the explicit lap_e and the implicit matrix in 2 and 3
 * dimensions): across side `side` of unit (i, j), either a filled
 * neighbour, whose index i' + nx j' (periodic edges wrapped) goes to *nb and
 * 0 is returned, or a ghost g_ghost = k g_e with k = +1 (Neumann: empty
 * neighbour, free edge, frictionless or symmetry wall, open outlet) or
 * k = -1 (Dirichlet: no-slip wall), and k is returned (*nb unset).
 * On a periodic axis of two units both sides along it lead to the same
 * neighbour (the mesh allows no periodic axis of one unit). */
int mpm_nonlocal_side(const mpm_nonlocal *ws, int i, int j, int side, size_t *nb);

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

/* 1 if unit (i, j) holds dense mass. */
static inline int mpm_nonlocal_filled(const mpm_nonlocal *ws, int i, int j)
{
  return ws->sm[i + ws->nx * j] > 0.0;
}

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
